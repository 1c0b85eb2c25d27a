// The global sizing options in one table: name, member, default (the
// member's initial value), help text, and the command-line range check where
// the command line refuses a value itself (exit 2) rather than the
// validation (exit 1). The table drives the command line (app/cli_options.cpp), the
// config file's global keys (sizing/params.cpp), and the option list of
// docs/options.md is checked against it by a test.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "sizing/params.h"
#include "sizing/size_map.h"

namespace sizemesh {

struct SizingOption {
  std::string key;                        // config key
  std::string flag;                       // command-line flag
  double SizingParams::*number = nullptr;  // a number, or
  bool SizingParams::*on = nullptr;        // a switch, on by default: the flag turns it off, or
  std::vector<std::string> choices;       // one word of these (read and written through set/get)
  std::string help;
  double cli_lo = 0, cli_hi = 0;          // command-line range when cli_lo < cli_hi
  void (*set)(SizingParams&, const std::string&) = nullptr;  // choices: store a word (one of them)
  std::string (*get)(const SizingParams&) = nullptr;         // choices: the word stored
};

const std::vector<SizingOption>& sizing_options();

// The command-line flag of the sizing option with this config key (throws
// Error on a key the table does not have).
const std::string& flag_of(const std::string& key);

// The options to change when sizes set by `l` ask for too many triangles,
// named by their flags ("--phi-c or --deviation"); empty for the far field's
// size, which is not a sizing option.
std::string remedy(Limit l);

// Reads the JSON config at `path` into p; the options named in `from_cli`
// (keys) keep the values p had: a flag on the command line wins over the file.
void apply_config(const std::string& path, const std::set<std::string>& from_cli, SizingParams& p);

}  // namespace sizemesh
