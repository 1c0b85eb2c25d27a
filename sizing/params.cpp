#include "sizing/params.h"

#include <algorithm>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <nlohmann/json.hpp>
#include <set>

#include "core/types.h"
#include "sizing/options.h"

namespace sizemesh {

namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void check_phi(double phi, const std::string& where) {
  if (!(phi > 0 && phi < 180)) throw Error(where + "phi_c must be in (0, 180) degrees, got " + num(phi));
}
void check_mu(double mu, const std::string& where) {
  if (!(mu > 0) || !std::isfinite(mu)) throw Error(where + "mu_d must be positive, got " + num(mu));
}
void check_beta(double beta, const std::string& where) {
  if (!(beta >= 1) || !std::isfinite(beta)) throw Error(where + "beta must be at least 1, got " + num(beta));
}
template <class T>
void check_ids(const std::map<int, T>& m, int count, const std::string& kind) {
  for (const auto& [id, v] : m)
    if (id < 1 || id > count)
      throw Error("config names " + kind + " " + std::to_string(id) + " but the model has " + std::to_string(count) +
                  " " + kind + "s");
}
void check_size(const std::map<int, UserSize>& m, const std::string& kind) {
  for (const auto& [id, s] : m)
    if (s.expression.empty() && !(s.value > 0 && std::isfinite(s.value)))
      throw Error("size of " + kind + " " + std::to_string(id) + " must be positive, got " + num(s.value));
}

using nlohmann::json;

int parse_id(const std::string& key, const std::string& section) {
  size_t pos = 0;
  int id = 0;
  try {
    id = std::stoi(key, &pos);
  } catch (const std::logic_error&) {  // std::stoi: not a number, or out of range
    pos = 0;
  }
  if (pos != key.size() || key.empty()) throw Error("config: '" + section + "' key '" + key + "' is not an id");
  return id;
}

double number(const json& j, const std::string& what) {
  if (!j.is_number()) throw Error("config: " + what + " must be a number");
  return j.get<double>();
}

UserSize user_size(const json& j, const std::string& what) {
  UserSize s;
  if (j.is_number()) s.value = j.get<double>();
  else if (j.is_string()) s.expression = j.get<std::string>();
  else throw Error("config: " + what + " must be a number or an expression string");
  return s;
}

// Reads {"<id>": value, ...} into m.
template <class T, class F>
void read_map(const json& j, const std::string& section, std::map<int, T>& m, F convert) {
  if (!j.is_object()) throw Error("config: '" + section + "' must be an object of id: value");
  for (auto it = j.begin(); it != j.end(); ++it)
    m[parse_id(it.key(), section)] = convert(it.value(), section + "." + it.key());
}

Vec3 point3(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw Error("config: " + what + " must be a list of three numbers [x, y, z]");
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

// "sources": [{"type": "box", "min": [..], "max": [..], "size": h, "grow": r}, ...]
std::vector<SizeSource> read_sources(const json& j) {
  if (!j.is_array()) throw Error("config: 'sources' must be a list of objects");
  std::vector<SizeSource> out;
  for (size_t i = 0; i < j.size(); ++i) {
    const json& o = j[i];
    const std::string what = "sources[" + std::to_string(i) + "]";
    if (!o.is_object() || !o.contains("type") || !o["type"].is_string())
      throw Error("config: " + what + " must be an object with a \"type\" (point, sphere, line, cylinder or box)");
    const std::string type = o["type"].get<std::string>();
    SizeSource s;
    std::vector<std::string> keys;
    if (type == "point" || type == "sphere") {
      s.kind = type == "point" ? SizeSource::Kind::Point : SizeSource::Kind::Sphere;
      keys = {"center", "radius"};
    } else if (type == "line" || type == "cylinder") {
      s.kind = type == "line" ? SizeSource::Kind::Line : SizeSource::Kind::Cylinder;
      keys = {"from", "to", "radius"};
    } else if (type == "box") {
      s.kind = SizeSource::Kind::Box;
      keys = {"min", "max"};
    } else {
      throw Error("config: " + what + " has type '" + type + "'; use point, sphere, line, cylinder or box");
    }
    keys.push_back("size");
    for (const std::string& k : keys)
      if (!o.contains(k)) throw Error("config: " + what + " (" + type + ") needs \"" + k + "\"");
    for (auto it = o.begin(); it != o.end(); ++it)
      if (it.key() != "type" && it.key() != "grow" && std::find(keys.begin(), keys.end(), it.key()) == keys.end())
        throw Error("config: " + what + " (" + type + ") has unknown key '" + it.key() + "'");
    if (o.contains("center")) s.a = point3(o["center"], what + ".center");
    if (o.contains("from")) s.a = point3(o["from"], what + ".from");
    if (o.contains("to")) s.b = point3(o["to"], what + ".to");
    if (o.contains("min")) s.a = point3(o["min"], what + ".min");
    if (o.contains("max")) s.b = point3(o["max"], what + ".max");
    if (o.contains("radius")) s.radius = number(o["radius"], what + ".radius");
    s.size = number(o["size"], what + ".size");
    if (o.contains("grow")) s.grow = number(o["grow"], what + ".grow");
    validate_source(s, "config: " + what);
    out.push_back(s);
  }
  return out;
}

}  // namespace

void validate(const SizingParams& p, double diagonal, int points, int curves, int faces) {
  check_phi(p.phi_c_deg, "");
  check_mu(p.mu_d, "");
  check_beta(p.beta, "");
  const double h_min = p.resolved_h_min(diagonal), h_max = p.resolved_h_max(diagonal);
  if (!(h_min > 0) || !std::isfinite(h_min)) throw Error("h_min must be positive, got " + num(h_min));
  if (!(p.feature_angle_deg > 0 && p.feature_angle_deg < 180))
    throw Error("feature_angle must be in (0, 180) degrees, got " + num(p.feature_angle_deg));
  if (!(h_max > 0) || !std::isfinite(h_max)) throw Error("h_max must be positive, got " + num(h_max));
  if (h_min > h_max) throw Error("h_min (" + num(h_min) + ") is larger than h_max (" + num(h_max) + ")");
  if (!(p.deviation >= 0) || !std::isfinite(p.deviation))
    throw Error("deviation must be zero (none) or positive, got " + num(p.deviation));
  for (const double* s : {&p.le_spacing, &p.te_spacing, &p.tip_spacing})
    if (!(*s >= 0 && *s < 1))
      throw Error(std::string(s == &p.le_spacing ? "le_spacing" : s == &p.te_spacing ? "te_spacing" : "tip_spacing") +
                  " must be a share of the chord in [0, 1) (0: off), got " + num(*s));
  if (!(p.te_cells >= 0 && p.te_cells <= 1000))
    throw Error("te_cells must be a count of elements in [0, 1000] (0: off), got " + num(p.te_cells));
  if (!(p.max_triangles >= 1) || !std::isfinite(p.max_triangles))
    throw Error("max_triangles must be at least 1, got " + num(p.max_triangles));
  for (const auto& [id, v] : p.curve_phi_c_deg) check_phi(v, "curve " + std::to_string(id) + ": ");
  for (const auto& [id, v] : p.face_phi_c_deg) check_phi(v, "face " + std::to_string(id) + ": ");
  for (const auto& [id, v] : p.face_mu_d) check_mu(v, "face " + std::to_string(id) + ": ");
  for (const auto& [id, v] : p.face_beta) check_beta(v, "face " + std::to_string(id) + ": ");
  check_ids(p.curve_phi_c_deg, curves, "curve");
  check_ids(p.face_phi_c_deg, faces, "face");
  check_ids(p.face_mu_d, faces, "face");
  check_ids(p.face_beta, faces, "face");
  check_ids(p.point_size, points, "point");
  check_ids(p.curve_size, curves, "curve");
  check_ids(p.face_size, faces, "face");
  check_size(p.point_size, "point");
  check_size(p.curve_size, "curve");
  check_size(p.face_size, "face");
  for (size_t i = 0; i < p.sources.size(); ++i) validate_source(p.sources[i], "source " + std::to_string(i + 1));
}

void remap_face_ids(SizingParams& p, const std::vector<int>& source, int sewn_faces) {
  std::vector<std::vector<int>> pieces(sewn_faces + 1);
  for (size_t f = 0; f < source.size(); ++f)
    if (source[f] >= 1 && source[f] <= sewn_faces) pieces[source[f]].push_back(static_cast<int>(f) + 1);
  auto remap = [&](auto& by_face) {
    check_ids(by_face, sewn_faces, "face");
    std::remove_reference_t<decltype(by_face)> out;
    for (const auto& [id, v] : by_face)
      for (int f : pieces[id]) out[f] = v;
    by_face = std::move(out);
  };
  remap(p.face_phi_c_deg);
  remap(p.face_mu_d);
  remap(p.face_beta);
  remap(p.face_size);
}

const char* gap_side_name(GapSide s) {
  switch (s) {
    case GapSide::Fluid: return "fluid";
    case GapSide::Solid: return "solid";
    case GapSide::Both: return "both";
    default: return "auto";
  }
}

GapSide gap_side_from(const std::string& name) {
  for (GapSide s : {GapSide::Auto, GapSide::Fluid, GapSide::Solid, GapSide::Both})
    if (name == gap_side_name(s)) return s;
  throw Error("gap side must be auto, fluid, solid or both, got '" + name + "'");
}

void read_config(const std::string& path, SizingParams& p) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read config file '" + path + "'");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::parse_error& e) {
    throw Error("config file '" + path + "' is not valid JSON: " + e.what());
  }
  if (!j.is_object()) throw Error("config file '" + path + "' must hold a JSON object");
  std::set<std::string> known = {"curve_phi_c", "face_phi_c", "face_mu_d", "face_beta",
                                 "point_size",  "curve_size", "face_size", "sources"};
  for (const SizingOption& o : sizing_options()) known.insert(o.key);
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!known.count(it.key())) throw Error("config: unknown key '" + it.key() + "'");
  for (const SizingOption& o : sizing_options()) {
    if (!j.contains(o.key)) continue;
    if (o.number) p.*o.number = number(j[o.key], o.key);
    if (o.on) {
      if (!j[o.key].is_boolean()) throw Error("config: " + o.key + " must be true or false");
      p.*o.on = j[o.key].get<bool>();
    }
    if (o.set) {
      std::string words;
      for (const std::string& w : o.choices) words += (words.empty() ? "" : ", ") + w;
      if (!j[o.key].is_string()) throw Error("config: " + o.key + " must be a string (" + words + ")");
      const std::string w = j[o.key].get<std::string>();
      if (std::find(o.choices.begin(), o.choices.end(), w) == o.choices.end())
        throw Error("config: " + o.key + " must be one of " + words + ", got '" + w + "'");
      o.set(p, w);
    }
  }
  if (j.contains("curve_phi_c")) read_map(j["curve_phi_c"], "curve_phi_c", p.curve_phi_c_deg, number);
  if (j.contains("face_phi_c")) read_map(j["face_phi_c"], "face_phi_c", p.face_phi_c_deg, number);
  if (j.contains("face_mu_d")) read_map(j["face_mu_d"], "face_mu_d", p.face_mu_d, number);
  if (j.contains("face_beta")) read_map(j["face_beta"], "face_beta", p.face_beta, number);
  if (j.contains("point_size")) read_map(j["point_size"], "point_size", p.point_size, user_size);
  if (j.contains("curve_size")) read_map(j["curve_size"], "curve_size", p.curve_size, user_size);
  if (j.contains("face_size")) read_map(j["face_size"], "face_size", p.face_size, user_size);
  if (j.contains("sources")) {
    const std::vector<SizeSource> more = read_sources(j["sources"]);
    p.sources.insert(p.sources.end(), more.begin(), more.end());
  }
}

void size_domain_faces(SizingParams& p, const std::vector<int>& domain_faces, double element_size) {
  if (!(element_size > 0)) return;
  for (int f : domain_faces) {
    p.face_h_max[f] = element_size;
    p.edge_graded_faces.insert(f);
  }
}

AccuracyRules accuracy_rules(const SizingParams& p, double h_min, int faces) {
  AccuracyRules r;
  r.deviation = p.deviation;
  r.h_min = h_min;
  r.max_turn.assign(faces + 1, 0.0);
  r.size_slope.assign(faces + 1, 0.0);
  for (int f = 1; f <= faces; ++f) {
    r.max_turn[f] = p.face_phi_c(f) * kPi / 180.0;
    const auto beta = p.face_beta.find(f);
    r.size_slope[f] = std::log(beta == p.face_beta.end() ? p.beta : beta->second);
  }
  return r;
}

}  // namespace sizemesh
