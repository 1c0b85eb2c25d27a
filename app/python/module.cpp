// The Python module `sizemesh`: the same library and options as the command
// line, with the results as NumPy arrays. Keyword arguments are the command
// line's flags (h_min=... for --h-min, sew=False for --no-sew), parsed by the
// command line's own parser, so names, defaults and checks are the same.
// Loading, sizing and meshing run without the GIL: Python threads mesh
// models side by side.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "app/cli_options.h"
#include "io/mesh_output.h"
#include "io/report.h"
#include "io/vtu_writer.h"

namespace py = pybind11;
using namespace sizemesh;

namespace {

// The command line's text for a Python value.
std::string as_text(const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)) return py::repr(v).cast<std::string>();
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::hasattr(v, "__fspath__")) return py::str(v.attr("__fspath__")()).cast<std::string>();
  throw Error("option values are numbers, booleans or strings, got " + py::repr(v).cast<std::string>());
}

// Options of one run from a path and keyword arguments, through the command line's parser.
RunOptions options_for(const py::object& path, const py::kwargs& kwargs) {
  std::vector<std::pair<std::string, std::string>> given;
  bool quiet_given = false;
  for (const auto& [k, v] : kwargs) {
    const std::string name = k.cast<std::string>();
    for (const char* file_option : {"output", "report", "background", "info", "version", "help"})
      if (name == file_option) throw Error("'" + name + "' is not an option here: use sizemesh.write() for files");
    quiet_given = quiet_given || name == "quiet";
    // A list gives the flag once per item (source=['box ...', 'sphere ...']).
    if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v))
      for (const py::handle& item : v) given.emplace_back(name, as_text(item));
    else
      given.emplace_back(name, as_text(v));
  }
  if (!quiet_given) given.emplace_back("quiet", "true");
  CLI::App app{"sizemesh"};
  RunCommandLine cl;
  add_run_options(app, cl);
  std::vector<std::string> args = arguments_for(app, given);
  args.insert(args.begin(), as_text(path));
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    throw Error(e.what());
  }
  finish_run_options(app, cl);
  return cl.options;
}

template <typename T>
py::array_t<T> column(const std::vector<T>& v) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::array_t<double> points_of(const std::vector<Vec3>& xyz) {
  py::array_t<double> a({static_cast<py::ssize_t>(xyz.size()), py::ssize_t{3}});
  auto w = a.mutable_unchecked<2>();
  for (size_t i = 0; i < xyz.size(); ++i)
    for (int k = 0; k < 3; ++k) w(i, k) = xyz[i][k];
  return a;
}

py::array_t<int64_t> triangles_of(const std::vector<std::array<int, 3>>& tris) {
  py::array_t<int64_t> a({static_cast<py::ssize_t>(tris.size()), py::ssize_t{3}});
  auto w = a.mutable_unchecked<2>();
  for (size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) w(i, k) = tris[i][k];
  return a;
}

py::object to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

// A run's results, shared by the Python objects that look into them.
struct Run {
  std::shared_ptr<RunResult> result;
  RunOptions options;
};

Run sized(const py::object& path, const py::kwargs& kwargs) {
  Run run{nullptr, options_for(path, kwargs)};
  py::gil_scoped_release unlocked;
  std::vector<std::string> warnings;
  std::unique_ptr<RunResult> r = size_model(run.options, [&warnings](const std::string& w) { warnings.push_back(w); });
  r->warnings = std::move(warnings);
  run.result = std::move(r);
  return run;
}

struct Mesh : Run {
  py::array_t<double> points() const { return points_of(result->mesh.xyz); }
  py::array_t<int64_t> triangles() const { return triangles_of(result->mesh.tris); }
  py::array_t<int> face_ids() const { return column(result->mesh.tri_face); }
  py::array_t<int> markers() const {
    const MeshLabels labels = result->labels();
    std::vector<int> out(result->mesh.tri_face.size());
    for (size_t t = 0; t < out.size(); ++t) out[t] = labels.marker_of(result->mesh.tri_face[t]);
    return column(out);
  }
  py::array_t<double> min_angle() const { return column(result->report.quality.min_angle); }
  py::array_t<int> sliver() const {
    const auto& s = result->report.quality.sliver;
    return column(std::vector<int>(s.begin(), s.end()));
  }
  py::array_t<double> target_size() const { return column(result->target); }
  py::array_t<int> limited_by() const {
    return column(std::vector<int>(result->limited_by.begin(), result->limited_by.end()));
  }
  py::object report() const { return to_python(report_json(result->report)); }
  std::vector<std::pair<int, std::string>> failures() const {
    std::vector<std::pair<int, std::string>> out;
    for (const auto& f : result->mesh.failures) out.emplace_back(f.face, f.reason);
    return out;
  }
  void write(const std::string& path) const {
    check_writable(path);
    check_mesh_format(path);
    py::gil_scoped_release unlocked;
    write_mesh(path, result->mesh, result->labels(), result->report.quality, result->target, result->limited_by);
  }
  py::object to_meshio() const {
    py::module_ meshio = py::module_::import("meshio");
    py::list cells;
    cells.append(py::make_tuple("triangle", triangles()));
    py::dict cell_data, point_data;
    auto one = [](const py::object& a) {
      py::list l;
      l.append(a);
      return l;
    };
    cell_data["face_id"] = one(face_ids());
    cell_data["marker"] = one(markers());
    cell_data["min_angle"] = one(min_angle());
    cell_data["sliver"] = one(sliver());
    point_data["target_size"] = target_size();
    point_data["limited_by"] = limited_by();
    return meshio.attr("Mesh")(points(), cells, py::arg("point_data") = point_data, py::arg("cell_data") = cell_data);
  }
};

struct SizeMapView : Run {
  py::array_t<double> points() const { return points_of(result->bg.xyz); }
  py::array_t<int64_t> triangles() const { return triangles_of(result->bg.tris); }
  py::array_t<int> face_ids() const { return column(result->bg.tri_face); }
  py::array_t<double> sizes() const { return column(result->sizes.h); }
  py::array_t<double> initial_sizes() const { return column(result->sizes.h_initial); }
  std::vector<std::string> limited_by() const {
    std::vector<std::string> out;
    for (Limit l : result->sizes.limit) out.push_back(limit_name(l));
    return out;
  }
  // One face's background vertices: their (u, v) on it and their indices.
  py::tuple face_uv(int face) const {
    check_face(face);
    const FacePatch& patch = result->bg.patches[face - 1];
    py::array_t<double> uv({static_cast<py::ssize_t>(patch.uv.size()), py::ssize_t{2}});
    auto w = uv.mutable_unchecked<2>();
    for (size_t i = 0; i < patch.uv.size(); ++i) w(i, 0) = patch.uv[i].x(), w(i, 1) = patch.uv[i].y();
    return py::make_tuple(uv, column(patch.vertex));
  }
  void check_face(int face) const {
    if (face < 1 || face > result->model->num_faces())
      throw Error("face " + std::to_string(face) + " is not in the model (1.." +
                  std::to_string(result->model->num_faces()) + ")");
  }
  // The size at each (u, v) of one face: the walk-through search (paper 4.2),
  // each point starting from the previous one's triangle.
  py::array_t<double> query(int face, const py::array_t<double, py::array::c_style | py::array::forcecast>& uv) {
    if (uv.ndim() != 2 || uv.shape(1) != 2) throw Error("uv must be an array of shape (n, 2)");
    check_face(face);
    if (!result->query) result->query.emplace(size_query_for(*result->model, result->bg, result->sizes.h));
    const auto in = uv.unchecked<2>();
    py::array_t<double> out(in.shape(0));
    auto w = out.mutable_unchecked<1>();
    std::vector<Vec2> points(in.shape(0));
    for (py::ssize_t i = 0; i < in.shape(0); ++i) points[i] = Vec2(in(i, 0), in(i, 1));
    std::vector<double> h(points.size());
    {
      py::gil_scoped_release unlocked;
      int hint = -1;
      for (size_t i = 0; i < points.size(); ++i) h[i] = result->query->at(face, points[i], hint);
    }
    for (size_t i = 0; i < h.size(); ++i) w(i) = h[i];
    return out;
  }
};

Mesh mesh(const py::object& path, const py::kwargs& kwargs) {
  Run run = sized(path, kwargs);
  {
    py::gil_scoped_release unlocked;
    std::vector<std::string>& warnings = run.result->warnings;
    mesh_model(*run.result, run.options, [&warnings](const std::string& w) { warnings.push_back(w); });
  }
  Mesh m;
  static_cast<Run&>(m) = std::move(run);
  return m;
}

// The levels of a mesh family (sizing/family.h), coarsest first, from one sized run.
std::vector<Mesh> mesh_family(const py::object& path, int levels, double ratio, const py::kwargs& kwargs) {
  if (levels < 1 || levels > 8) throw Error("levels must be 1 to 8, got " + std::to_string(levels));
  if (!(ratio >= 1.1 && ratio <= 16)) throw Error("ratio must be 1.1 to 16, got " + std::to_string(ratio));
  Run run = sized(path, kwargs);
  std::vector<Mesh> out;
  for (int level = 1; level <= levels; ++level) {
    Mesh m;
    m.options = run.options;
    {
      py::gil_scoped_release unlocked;
      std::shared_ptr<RunResult> r = family_level(*run.result, level, levels, ratio);
      std::vector<std::string>& warnings = r->warnings;
      mesh_model(*r, run.options, [&warnings](const std::string& w) { warnings.push_back(w); });
      m.result = std::move(r);
    }
    out.push_back(std::move(m));
  }
  return out;
}

py::dict info_of(const Model& model) {
  const ModelInfo& i = model.info();
  py::dict d;
  d["path"] = i.path;
  d["format"] = i.format;
  d["unit"] = i.unit;
  d["faces"] = i.faces;
  d["curves"] = i.curves;
  d["points"] = i.points;
  d["solids"] = i.solids;
  d["closed"] = model.closed();
  d["bbox_min"] = py::make_tuple(i.bbox_min.x(), i.bbox_min.y(), i.bbox_min.z());
  d["bbox_max"] = py::make_tuple(i.bbox_max.x(), i.bbox_max.y(), i.bbox_max.z());
  d["diagonal"] = i.diagonal();
  d["components"] = i.preparation.components.size();
  return d;
}

}  // namespace

PYBIND11_MODULE(sizemesh, m) {
  m.doc() = "sizemesh: element sizing from CAD geometry and surface meshing (the sizemesh command's library)";
  m.attr("__version__") = SIZEMESH_VERSION;
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      error(e.what());
    }
  });

  py::class_<Mesh>(m, "Mesh", "A surface mesh and its report; a partial mesh lists its failed faces")
      .def_property_readonly("points", &Mesh::points, "node coordinates, (n, 3) float64")
      .def_property_readonly("triangles", &Mesh::triangles, "node indices, (m, 3) int64")
      .def_property_readonly("face_ids", &Mesh::face_ids, "the model face of each triangle")
      .def_property_readonly("markers", &Mesh::markers,
                             "each triangle's marker: its source face id, or past them the far field and symmetry")
      .def_property_readonly("min_angle", &Mesh::min_angle, "smallest angle of each triangle, degrees")
      .def_property_readonly("sliver", &Mesh::sliver,
                             "per triangle: 0 not under 12 degrees, 1 forced by the CAD, 2 avoidable")
      .def_property_readonly("target_size", &Mesh::target_size, "the size map's size at each node")
      .def_property_readonly("limited_by", &Mesh::limited_by,
                             "the rule behind each node's size (codes as SizeMap.limited_by's names, in order)")
      .def_property_readonly("report", &Mesh::report, "the JSON report of the command line, as a dict")
      .def_property_readonly("failures", &Mesh::failures, "faces that could not be meshed: (face, reason)")
      .def_property_readonly("warnings", [](const Mesh& x) { return x.result->warnings; })
      .def("write", &Mesh::write, py::arg("path"), "write as .vtu, .msh, .stl, .cgns, .mesh or .smesh")
      .def("to_meshio", &Mesh::to_meshio, "the mesh as a meshio.Mesh (needs meshio)");

  py::class_<SizeMapView>(m, "SizeMap", "The smoothed size map on the background mesh (paper 3)")
      .def_property_readonly("points", &SizeMapView::points, "background vertices, (n, 3)")
      .def_property_readonly("triangles", &SizeMapView::triangles, "background triangles, (m, 3)")
      .def_property_readonly("face_ids", &SizeMapView::face_ids, "the model face of each background triangle")
      .def_property_readonly("sizes", &SizeMapView::sizes, "smoothed size at each vertex")
      .def_property_readonly("initial_sizes", &SizeMapView::initial_sizes, "size before smoothing at each vertex")
      .def_property_readonly("limited_by", &SizeMapView::limited_by, "what set each vertex's initial size")
      .def_property_readonly("h_min", [](const SizeMapView& s) { return s.result->sizes.h_min; })
      .def_property_readonly("h_max", [](const SizeMapView& s) { return s.result->sizes.h_max; })
      .def_property_readonly("estimated_triangles", [](const SizeMapView& s) { return s.result->estimate.total; })
      .def_property_readonly("model", [](const SizeMapView& s) { return info_of(*s.result->model); })
      .def("face_uv", &SizeMapView::face_uv, py::arg("face"),
           "(uv, vertex): a face's background vertices, their (u, v) on it and their indices into points")
      .def("query", &SizeMapView::query, py::arg("face"), py::arg("uv"),
           "sizes at the (n, 2) parameters uv of one face (1-based id)");

  m.def("mesh", &mesh, py::arg("path"),
        "Mesh a STEP, IGES or BREP file; keyword arguments are the command line's options "
        "(h_min=0.1 for --h-min, sew=False for --no-sew, farfield='sphere', ...)");
  m.def("mesh_family", &mesh_family, py::arg("path"), py::arg("levels") = 3, py::arg("ratio") = 3.0,
        "A mesh family for grid-convergence studies: `levels` meshes, coarsest first, from one size map scaled "
        "so that each has about `ratio` times the triangles of the one before (the middle level is the map as "
        "built); keyword arguments as for mesh()");
  m.def(
      "size_map",
      [](const py::object& path, const py::kwargs& kwargs) {
        SizeMapView s;
        static_cast<Run&>(s) = sized(path, kwargs);
        return s;
      },
      py::arg("path"), "The smoothed size map of a model, without meshing it");
  m.def(
      "load",
      [](const py::object& path, const py::kwargs& kwargs) {
        const RunOptions o = options_for(path, kwargs);
        std::unique_ptr<Model> model;
        {
          py::gil_scoped_release unlocked;
          model = std::make_unique<Model>(load_model(o.input, o.load));
        }
        return info_of(*model);
      },
      py::arg("path"), "Load and prepare a model; returns what --info prints, as a dict");
  m.def(
      "background_mesh",
      [](const py::object& path, const py::kwargs& kwargs) {
        const RunOptions o = options_for(path, kwargs);
        py::gil_scoped_release unlocked;
        const Model model = load_model(o.input, o.load);
        BackgroundMesh bg = build_background_mesh(model, o.tessellation);
        py::gil_scoped_acquire locked;
        py::dict d;
        d["points"] = points_of(bg.xyz);
        d["triangles"] = triangles_of(bg.tris);
        d["face_ids"] = column(bg.tri_face);
        d["classification_dim"] = column(std::vector<int>(bg.dim.begin(), bg.dim.end()));
        d["classification_id"] = column(std::vector<int>(bg.entity.begin(), bg.entity.end()));
        return d;
      },
      py::arg("path"), "The classified background mesh (OCCT tessellation) as arrays");
  m.def("write", [](const Mesh& mesh, const std::string& path) { mesh.write(path); }, py::arg("mesh"),
        py::arg("path"), "write a mesh as .vtu, .msh, .stl, .cgns, .mesh or .smesh");
}
