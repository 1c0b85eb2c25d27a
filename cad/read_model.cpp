// Reading STEP, IGES and BREP files into a Model (format by content, then extension).
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Interface_Static.hxx>
#include <StepData_StepModel.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <OSD.hxx>
#include <Standard_ErrorHandler.hxx>
#include <STEPControl_Reader.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TopExp_Explorer.hxx>
#include <UnitsMethods.hxx>
#include <TopoDS.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <iterator>
#include <optional>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <map>

#include "cad/iges_layout.h"
#include "cad/occt_model.h"

namespace sizemesh {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

enum class Format { Step, Iges, Brep, Unknown };

// OpenCASCADE prints progress and warnings to stdout; sizemesh speaks for
// itself. Its readers can also fault on corrupt data: signals become
// Standard_Failure inside OCC_CATCH_SIGNALS blocks.
void prepare_occt() {
  static std::once_flag once;  // Python threads may load models at the same time
  std::call_once(once, [] {
    const Handle(Message_Messenger)& m = Message::DefaultMessenger();
    m->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    OSD::SetSignal(false);
  });
}

// The last bytes of a file, to see whether it ends as its format requires.
std::string tail_of(const std::string& path, size_t n) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in.tellg();
  const std::streamoff start = size > static_cast<std::streamoff>(n) ? size - static_cast<std::streamoff>(n) : 0;
  in.seekg(start);
  std::string t(static_cast<size_t>(size - start), '\0');
  in.read(t.data(), static_cast<std::streamsize>(t.size()));
  return t;
}

// A STEP file ends with END-ISO-10303-21; and an IGES file with its T
// (terminate) record: without them the file was cut short.
void check_complete(const std::string& path, Format f) {
  if (f == Format::Step) {
    if (tail_of(path, 4096).find("END-ISO-10303-21;") == std::string::npos)
      throw Error("'" + path + "' is truncated: a STEP file ends with END-ISO-10303-21;");
  } else if (f == Format::Iges) {
    std::string t = tail_of(path, 512);
    while (!t.empty() && (t.back() == '\n' || t.back() == '\r' || t.back() == ' ')) t.pop_back();
    const size_t line = t.rfind('\n');
    const std::string last = t.substr(line == std::string::npos ? 0 : line + 1);
    if (last.size() < 73 || last[72] != 'T')
      throw Error("'" + path + "' is truncated: an IGES file ends with its T (terminate) record");
  }
}

Format format_from_content(const std::string& head) {
  if (head.find("ISO-10303-21") != std::string::npos) return Format::Step;
  if (head.find("DBRep_DrawableShape") != std::string::npos ||
      head.find("CASCADE Topology") != std::string::npos)
    return Format::Brep;
  // IGES: fixed 80-column records with the section letter in column 73.
  std::string first = head.substr(0, head.find('\n'));
  if (!first.empty() && first.back() == '\r') first.pop_back();
  if (first.size() >= 73 && first[72] == 'S') return Format::Iges;
  return Format::Unknown;
}

Format format_from_extension(const std::string& ext) {
  if (ext == ".stp" || ext == ".step") return Format::Step;
  if (ext == ".igs" || ext == ".iges") return Format::Iges;
  if (ext == ".brep" || ext == ".brp") return Format::Brep;
  return Format::Unknown;
}

const char* format_name(Format f) {
  switch (f) {
    case Format::Step: return "STEP";
    case Format::Iges: return "IGES";
    case Format::Brep: return "BREP";
    default: return "unknown";
  }
}

// STEP length-unit names to (display name, translator name); longest name first
// so that MILLIMETRE is not taken for METRE.
std::pair<std::string, std::string> step_unit(const std::string& name) {
  static const std::vector<std::pair<std::string, std::pair<std::string, std::string>>> units = {
      {"MICROMETRE", {"um", "UM"}}, {"MILLIMETRE", {"mm", "MM"}}, {"CENTIMETRE", {"cm", "CM"}},
      {"KILOMETRE", {"km", "KM"}},  {"METRE", {"m", "M"}},        {"INCH", {"in", "INCH"}},
      {"FOOT", {"ft", "FT"}},       {"MILE", {"mi", "MI"}}};
  std::string up = name;
  std::transform(up.begin(), up.end(), up.begin(), [](unsigned char c) { return std::toupper(c); });
  for (const auto& [key, value] : units)
    if (up.find(key) != std::string::npos) return value;
  return {"mm", "MM"};
}

// Makes the translator produce lengths in the file's own unit. Both the static
// and the kernel's global unit are set before every transfer: a previous read
// may have left either one changed.
double unit_in_mm(const std::string& translator_name) {
  static const std::map<std::string, double> mm = {{"UM", 1e-3}, {"MM", 1.0},      {"CM", 10.0},  {"M", 1000.0},
                                                   {"KM", 1e6},  {"INCH", 25.4}, {"FT", 304.8}, {"MI", 1609344.0},
                                                   {"MIL", 0.0254}, {"UIN", 2.54e-5}};
  return mm.at(translator_name);
}

void set_target_unit(const std::string& translator_name) {
  Interface_Static::SetCVal("xstep.cascade.unit", translator_name.c_str());
  UnitsMethods::SetCasCadeLengthUnit(unit_in_mm(translator_name));
}

// IGES global-section unit flag to (display name, translator name).
std::pair<std::string, std::string> iges_unit(int flag) {
  switch (flag) {
    case 1: return {"in", "INCH"};
    case 4: return {"ft", "FT"};
    case 5: return {"mi", "MI"};
    case 6: return {"m", "M"};
    case 7: return {"km", "KM"};
    case 8: return {"mil", "MIL"};
    case 9: return {"um", "UM"};
    case 10: return {"cm", "CM"};
    case 11: return {"uin", "UIN"};
    default: return {"mm", "MM"};
  }
}

// Entities the reader failed on, while parsing (references, parameters) or
// translating (geometry it could not build): their count and the first one,
// named by its number in the file (STEP #id, IGES directory entry D-line).
void note_failures(const Handle(XSControl_WorkSession)& ws, ModelInfo& info) {
  if (ws.IsNull() || ws->Model().IsNull()) return;
  const Handle(Interface_InterfaceModel) model = ws->Model();
  const Handle(StepData_StepModel) step = Handle(StepData_StepModel)::DownCast(model);
  std::vector<Interface_CheckIterator> lists = {ws->ModelCheckList()};
  if (!ws->TransferReader().IsNull()) lists.push_back(ws->TransferReader()->LastCheckList());
  for (const Interface_CheckIterator& list : lists)
    for (list.Start(); list.More(); list.Next()) {
      const Handle(Interface_Check)& check = list.Value();
      if (check.IsNull() || !check->HasFailed()) continue;
      if (info.entities_failed++ > 0) continue;
      const int num = list.Number();
      Handle(Standard_Transient) ent = check->Entity();
      if (ent.IsNull() && num > 0 && num <= model->NbEntities()) ent = model->Value(num);
      std::string where;
      if (!ent.IsNull()) {
        where = step.IsNull() ? "directory entry D" + std::to_string(2 * model->Number(ent) - 1)
                              : "entity #" + std::to_string(step->IdentLabel(ent));
        where += std::string(" (") + model->TypeName(ent, Standard_False) + ")";
      } else if (num > 0) {
        where = "entity number " + std::to_string(num);
      }
      const char* why = check->CFail(1);
      info.first_failure = (where.empty() ? "" : where + ": ") + (why && *why ? why : "unreadable");
    }
}

// " (N entities could not be read; the first, ...)" or "".
std::string failure_note(const ModelInfo& info) {
  if (info.entities_failed == 0) return "";
  return " (" + std::to_string(info.entities_failed) + (info.entities_failed == 1 ? " entity" : " entities") +
         " could not be read; first: " + info.first_failure + ")";
}

TopoDS_Shape read_step(const std::string& path, ModelInfo& info,
                       std::vector<std::pair<TopoDS_Shape, std::string>>& names) {
  STEPControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) {
    note_failures(reader.WS(), info);
    throw Error("cannot parse STEP file '" + path + "' (truncated or malformed)" + failure_note(info));
  }
  TColStd_SequenceOfAsciiString length_units, angle_units, solid_angle_units;
  reader.FileUnits(length_units, angle_units, solid_angle_units);
  auto unit = step_unit(length_units.IsEmpty() ? "MILLIMETRE" : length_units.First().ToCString());
  info.unit = unit.first;
  set_target_unit(unit.second);
  if (reader.NbRootsForTransfer() == 0) {
    note_failures(reader.WS(), info);
    throw Error("STEP file '" + path + "' contains no geometry" + failure_note(info));
  }
  reader.TransferRoots();
  note_failures(reader.WS(), info);
  TopoDS_Shape shape = reader.OneShape();
  // Entity names (faces and solids), when the file gives them.
  Handle(XSControl_TransferReader) tr = reader.WS()->TransferReader();
  for (TopAbs_ShapeEnum kind : {TopAbs_SOLID, TopAbs_FACE}) {
    for (TopExp_Explorer ex(shape, kind); ex.More(); ex.Next()) {
      Handle(StepRepr_RepresentationItem) item =
          Handle(StepRepr_RepresentationItem)::DownCast(tr->EntityFromShapeResult(ex.Current(), 1));
      if (item.IsNull() || item->Name().IsNull() || item->Name()->Length() == 0) continue;
      std::string name = item->Name()->ToCString();
      if (name != "NONE") names.emplace_back(ex.Current(), name);
    }
  }
  return shape;
}

// A copy of an IGES file in the standard column layout, removed with this object.
struct RealignedIges {
  std::string path;
  ~RealignedIges() {
    std::error_code ec;
    if (!path.empty()) fs::remove(path, ec);
  }
};

// The path to read: the file itself, or a realigned copy of it when its
// parameter data run into column 65 (cad/iges_layout.h).
std::string iges_to_read(const std::string& path, ModelInfo& info, RealignedIges& copy) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::optional<IgesRealignment> fixed = realign_iges_parameters(text);
  if (!fixed) return path;
  std::error_code ec;
  copy.path = (fs::temp_directory_path(ec) / ("sizemesh-" + std::to_string(::getpid()) + "-" +
                                              std::to_string(reinterpret_cast<std::uintptr_t>(&copy)) + ".igs"))
                  .string();
  std::ofstream out(copy.path, std::ios::binary);
  out << fixed->text;
  if (!out.flush()) {
    copy.path.clear();
    return path;
  }
  info.read_repairs.push_back(std::to_string(fixed->lines_moved) +
                             " IGES parameter lines have data in column 65, where the entity pointer belongs: "
                             "read as if laid out in columns 1-64");
  return copy.path;
}

// The IGES reader fixes its length scale when it parses the file, so the file
// is read in millimetres and scaled to its own unit afterwards.
TopoDS_Shape read_iges(const std::string& path, ModelInfo& info) {
  set_target_unit("MM");
  IGESControl_Reader reader;
  RealignedIges copy;
  if (reader.ReadFile(iges_to_read(path, info, copy).c_str()) != IFSelect_RetDone) {
    note_failures(reader.WS(), info);
    throw Error("cannot parse IGES file '" + path + "' (truncated or malformed)" + failure_note(info));
  }
  auto unit = iges_unit(reader.IGESModel()->GlobalSection().UnitFlag());
  info.unit = unit.first;
  if (reader.NbRootsForTransfer() == 0) {
    note_failures(reader.WS(), info);
    throw Error("IGES file '" + path + "' contains no geometry" + failure_note(info));
  }
  reader.TransferRoots();
  note_failures(reader.WS(), info);
  TopoDS_Shape shape = reader.OneShape();
  const double scale = 1.0 / unit_in_mm(unit.second);
  if (scale == 1.0 || shape.IsNull()) return shape;
  gp_Trsf trsf;
  trsf.SetScale(gp_Pnt(0, 0, 0), scale);
  return BRepBuilderAPI_Transform(shape, trsf, true).Shape();
}

TopoDS_Shape read_brep(const std::string& path, ModelInfo& info) {
  TopoDS_Shape shape;
  BRep_Builder builder;
  if (!BRepTools::Read(shape, path.c_str(), builder))
    throw Error("cannot parse BREP file '" + path + "' (truncated or malformed)");
  info.unit = "unknown";  // BREP files carry no unit
  return shape;
}

}  // namespace

CadFile read_cad(const std::string& path, const LoadOptions& options) {
  prepare_occt();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error("no such file: '" + path + "'");
  if (fs::is_directory(path, ec)) throw Error("'" + path + "' is a directory, not a CAD file");
  if (!fs::is_regular_file(path, ec)) throw Error("'" + path + "' is not a regular file (a pipe or a device?)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open '" + path + "' for reading");
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  if (head.empty()) throw Error("'" + path + "' is empty");

  const std::string ext = lower(fs::path(path).extension().string());
  Format by_content = format_from_content(head);
  Format by_ext = format_from_extension(ext);
  if (by_content == Format::Unknown) {
    if (by_ext == Format::Unknown)
      throw Error("'" + path + "' is not a STEP, IGES or BREP file (unknown extension '" + ext + "')");
    throw Error("'" + path + "' does not look like a " + format_name(by_ext) + " file");
  }

  ModelInfo info;
  info.path = path;
  info.format = format_name(by_content);
  std::vector<std::pair<TopoDS_Shape, std::string>> names;
  TopoDS_Shape shape;
  check_complete(path, by_content);
  auto cannot_read = [&](const Standard_Failure& e) {
    const char* why = e.GetMessageString();
    return Error("cannot read '" + path + "': " + (why && *why ? why : e.DynamicType()->Name()));
  };
  {
    // The translators' length unit is a setting of the whole kernel: files
    // are read one at a time (Python threads may load several at once).
    static std::mutex reading;
    const std::lock_guard<std::mutex> one_at_a_time(reading);
    try {
      OCC_CATCH_SIGNALS
      switch (by_content) {
        case Format::Step: shape = read_step(path, info, names); break;
        case Format::Iges: shape = read_iges(path, info); break;
        default: shape = read_brep(path, info); break;
      }
    } catch (const Standard_Failure& e) {
      throw cannot_read(e);
    }
  }
  try {
    OCC_CATCH_SIGNALS
    if (shape.IsNull() || !TopExp_Explorer(shape, TopAbs_FACE).More())
      throw Error("'" + path + "' contains no surfaces to mesh" + failure_note(info));
    return sew_shape(shape, info, options, names);
  } catch (const Standard_Failure& e) {
    throw cannot_read(e);
  }
}

Model load_model(const std::string& path, const LoadOptions& options) {
  return prepare_model(read_cad(path, options), options);
}

}  // namespace sizemesh
