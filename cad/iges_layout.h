// IGES files whose parameter data run past column 64.
//
// An IGES parameter line holds data in columns 1-64 and the entity's
// directory pointer in columns 65-72. Some writers (pyGeo/pySpline among
// them) put 65 columns of data on a line, the last one a delimiter, and the
// pointer in columns 66-72. A strict reader drops column 65, so two numbers
// run together and the entity fails ("Real was expected"). This rewrites the
// parameter section in the standard layout: each entity's data re-wrapped at
// 64 columns on delimiters, the directory entries' pointers and line counts
// and the terminate record updated. Kernel-free: text in, text out.
#pragma once

#include <optional>
#include <string>

namespace sizemesh {

struct IgesRealignment {
  std::string text;      // the whole file in the standard layout
  int lines_moved = 0;   // parameter lines that had data in column 65
};

// The realigned file, or nothing when no parameter line has data in column
// 65 (or the file is not laid out in 80-column records this can rewrite).
std::optional<IgesRealignment> realign_iges_parameters(const std::string& file_text);

}  // namespace sizemesh
