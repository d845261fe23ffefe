// The garment_retarget._core module: the command line's commands run in this process, the
// OBJ reader and writer for NumPy arrays, and the batch's per-job runner for the cluster.
#include <signal.h>

#include <cstdio>
#include <string>
#include <vector>

#include <nanobind/eigen/dense.h>
#include <nanobind/nanobind.h>
#include <nanobind/stl/filesystem.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include "app/batch/batch_run.hpp"
#include "app/cli/commands.hpp"
#include "core/common/errors.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "core/io/obj_document.hpp"
#include "retarget/outcome.hpp"
#include "retarget/parameters.hpp"
#include "retarget/retarget.hpp"
#include "retarget/run/run_control.hpp"
#include "retarget/scene/shrink_avatar.hpp"
#include "retarget/validate_run.hpp"

namespace nb = nanobind;

namespace {

using RowMatrixX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMatrixX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// While alive, Ctrl-C and SIGTERM stop a running command at its next check (the command
/// then exits 10) instead of waiting for Python, which sees no signal while the command
/// runs without the GIL; Python's handlers come back after.
class SignalsStopRuns {
 public:
  SignalsStopRuns() {
    sigaction(SIGINT, nullptr, &python_interrupt_);
    sigaction(SIGTERM, nullptr, &python_terminate_);
    gr::clear_stop_request();
    gr::stop_on_signals();
  }
  ~SignalsStopRuns() {
    sigaction(SIGINT, &python_interrupt_, nullptr);
    sigaction(SIGTERM, &python_terminate_, nullptr);
  }
  SignalsStopRuns(const SignalsStopRuns&) = delete;
  SignalsStopRuns& operator=(const SignalsStopRuns&) = delete;

 private:
  struct sigaction python_interrupt_ {};
  struct sigaction python_terminate_ {};
};

/// Runs `garment-retarget ARGS...` in this process; returns its exit code. Errors raise as
/// the command line's would end it: UsageError, InputError, OutputError; an interrupted
/// command raises KeyboardInterrupt.
int run_command(const std::vector<std::string>& arguments) {
  int exit_code = 0;
  const std::unique_ptr<CLI::App> app = gr::make_command_line(exit_code);
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());
  try {
    {
      const SignalsStopRuns signals;
      const nb::gil_scoped_release unlocked;
      app->parse(reversed);
    }
    if (exit_code == gr::to_exit_code(gr::Outcome::kInterrupted)) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      throw nb::python_error();
    }
  } catch (const CLI::CallForHelp& e) {
    return app->exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app->exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app->exit(e);
  }
  std::fflush(stdout);
  return exit_code;
}

/// The OBJ's positions (#P×3, every `v` line) and triangles (#F×3, 0-based, polygons
/// fan-triangulated).
std::pair<RowMatrixX3d, RowMatrixX3i> read_mesh(const std::filesystem::path& path) {
  const gr::ObjDocument document = gr::read_obj(path.string());
  RowMatrixX3i faces(static_cast<Eigen::Index>(document.faces.size()), 3);
  for (std::size_t f = 0; f < document.faces.size(); ++f)
    for (int c = 0; c < 3; ++c)
      faces(static_cast<Eigen::Index>(f), c) = document.faces[f][c].position;
  return {document.positions, faces};
}

/// Writes V (#V×3) and F (#F×3, 0-based) as an OBJ at full precision.
void write_mesh(const std::filesystem::path& path, const RowMatrixX3d& vertices,
                const RowMatrixX3i& faces) {
  const auto bad = [&](const std::string& message) {
    return gr::InputError(path.string(), 0, message);
  };
  if (vertices.rows() == 0) throw bad("the mesh has no vertex");
  if (!vertices.allFinite()) throw bad("a vertex coordinate is not finite");
  if (faces.size() > 0 && (faces.minCoeff() < 0 || faces.maxCoeff() >= vertices.rows()))
    throw bad("a face index is out of range 0.." + std::to_string(vertices.rows() - 1));
  gr::ObjDocument document;
  document.source_path = path.string();
  document.positions = vertices;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    document.faces.push_back(
        {gr::ObjCorner{faces(f, 0)}, gr::ObjCorner{faces(f, 1)}, gr::ObjCorner{faces(f, 2)}});
  gr::write_obj(path.string(), document, document.positions);
}

const gr::BatchJob& find_job(const std::vector<gr::BatchJob>& jobs, const std::string& manifest,
                             const std::string& id) {
  for (const gr::BatchJob& job : jobs)
    if (job.id == id) return job;
  throw gr::InputError(manifest, 0, "no job \"" + id + "\"");
}

/// The ids of a manifest's jobs, in order, once the manifest is read and checked.
std::vector<std::string> manifest_ids(const std::string& manifest) {
  std::vector<gr::BatchJob> jobs = gr::read_manifest(manifest);
  gr::check_batch_options(manifest, jobs);
  std::vector<std::string> ids;
  for (const gr::BatchJob& job : jobs) ids.push_back(job.id);
  return ids;
}

nb::dict outcome_dict(const gr::JobOutcome& outcome) {
  nb::dict d;
  d["id"] = outcome.id;
  d["status"] = outcome.status;
  d["exit_code"] = outcome.exit_code;
  d["reused"] = outcome.reused;
  d["seconds"] = outcome.seconds;
  d["error"] = outcome.error;
  return d;
}

/// One job of a manifest, exactly as `garment-retarget batch` runs it.
nb::dict run_job(const std::string& manifest, const std::string& id, const std::string& out_dir,
                 const std::string& program, int threads) {
  std::vector<gr::BatchJob> jobs = gr::read_manifest(manifest);
  gr::check_batch_options(manifest, jobs);
  const gr::BatchJob& job = find_job(jobs, manifest, id);
  gr::JobOutcome outcome;
  {
    const nb::gil_scoped_release unlocked;
    outcome = gr::run_batch_job(job, gr::JobRunner{program, out_dir, threads});
  }
  return outcome_dict(outcome);
}

void write_summary(const std::string& manifest, const std::string& out_dir,
                   const std::vector<std::string>& reused_ids) {
  gr::write_batch_summary(out_dir, gr::read_manifest(manifest), reused_ids);
}

/// Every knob of parameter_table() that a run may set, as dicts: name (report.json key),
/// option (the keyword, with '_'), type, unit, help, range and the value per preset.
nb::list parameters() {
  nb::list rows;
  for (const gr::ParameterRow& row : gr::parameter_table()) {
    if (*row.option == '\0') continue;
    nb::dict d;
    d["name"] = row.name;
    std::string keyword = row.option;
    for (char& c : keyword)
      if (c == '-') c = '_';
    d["option"] = keyword;
    d["type"] = row.type == gr::ParameterType::kReal    ? "real"
                : row.type == gr::ParameterType::kCount ? "count"
                                                        : "switch";
    d["unit"] = row.unit;
    d["help"] = row.help;
    nb::dict presets;
    for (const gr::Quality quality :
         {gr::Quality::kFast, gr::Quality::kBalanced, gr::Quality::kAccurate})
      presets[gr::to_string(quality)] = row.get(gr::parameters_for_quality(quality));
    d["presets"] = presets;
    rows.append(d);
  }
  return rows;
}

/// The registered mesh formats (mesh_formats()), as dicts: name (a `format=` value),
/// extensions, and whether a file holds named meshes, several written meshes and skins.
nb::list formats() {
  nb::list rows;
  for (const gr::MeshFormat* format : gr::mesh_formats()) {
    nb::dict d;
    d["name"] = format->name;
    d["extensions"] = format->extensions;
    d["named_meshes"] = format->named_meshes;
    d["several_meshes"] = format->several_meshes;
    d["skinned"] = format->skinned;
    rows.append(d);
  }
  return rows;
}

/// `run(options)` in this process, without the GIL; Ctrl-C and SIGTERM stop it
/// (KeyboardInterrupt). A run stopped by its limits returns Outcome::kLimitReached with the
/// reason as its message.
template <class Result, class Options>
Result run_stoppable(Result (*run)(const Options&), const Options& options) {
  Result result;
  try {
    const SignalsStopRuns signals;
    const nb::gil_scoped_release unlocked;
    result = run(options);
  } catch (const gr::Interrupted& stopped) {
    if (gr::report_stopped_run(stopped) == gr::to_exit_code(gr::Outcome::kInterrupted)) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      throw nb::python_error();
    }
    result.status = gr::Outcome::kLimitReached;
    result.message = stopped.what();
  }
  return result;
}

/// Runs the retarget pipeline on typed options in this process, without the GIL; Ctrl-C
/// and SIGTERM stop it (KeyboardInterrupt). A run stopped by its limits returns
/// Outcome::kLimitReached with the reason as its message.
gr::RetargetResult run_retarget(const gr::RetargetOptions& options) {
  return run_stoppable(&gr::run_retarget, options);
}

/// Runs validate on typed options in this process, without the GIL.
gr::ValidateResult run_validate(const gr::ValidateOptions& options) {
  const nb::gil_scoped_release unlocked;
  return gr::run_validate(options);
}

/// A result's `status` (an Outcome), and its `exit_code` and `status_name` from the outcome
/// table.
template <class Result>
void bind_outcome(nb::class_<Result>& result) {
  result.def_ro("status", &Result::status)
      .def_prop_ro("exit_code", [](const Result& r) { return gr::to_exit_code(r.status); })
      .def_prop_ro("status_name", [](const Result& r) { return gr::to_string(r.status); });
}

/// Options.from_json(text): the options `from_json` makes of a JSON object's text.
template <class Options>
void bind_from_json(nb::class_<Options>& options, Options (*from_json)(const nlohmann::json&),
                    const char* doc) {
  options.def_static(
      "from_json",
      [from_json](const std::string& text) { return from_json(nlohmann::json::parse(text)); },
      nb::arg("text"), doc);
}

/// Binds validate's and shrink's typed options, their results and their runs on `m`.
void bind_validate_and_shrink(nb::module_& m) {
  nb::class_<gr::ValidateOptions> validate_options(
      m, "ValidateOptions", "Everything validate can be asked, typed and checked.");
  bind_from_json(validate_options, &gr::validate_options_from_json,
                 "The options from a JSON object of validate's long option names ('_' or '-'): "
                 "flags as booleans, repeatable options (garment, source) as arrays.");
  validate_options.def_ro("garments", &gr::ValidateOptions::garments)
      .def_ro("avatar", &gr::ValidateOptions::avatar)
      .def_ro("sources", &gr::ValidateOptions::sources)
      .def_ro("threshold", &gr::ValidateOptions::threshold)
      .def_ro("max_listed", &gr::ValidateOptions::max_listed);
  nb::class_<gr::ValidateResult> validate_result(m, "ValidateResult", "How a validation ended.");
  bind_outcome(validate_result);
  validate_result
      .def_prop_ro("certified", [](const gr::ValidateResult& r) { return gr::certified(r.status); })
      .def_prop_ro("report",
                   [](const gr::ValidateResult& r) {
                     return nb::module_::import_("json").attr("loads")(r.report.dump());
                   })
      .def_ro("summary", &gr::ValidateResult::summary)
      .def_ro("warnings", &gr::ValidateResult::warnings);
  m.def("run_validate", &run_validate, nb::arg("options"),
        "Runs validate on typed options in this process and returns its ValidateResult.");
  nb::class_<gr::ShrinkRunOptions> shrink_options(
      m, "ShrinkOptions", "Everything shrink can be asked, typed and checked.");
  bind_from_json(shrink_options, &gr::shrink_options_from_json,
                 "The options from a JSON object of shrink's long option names ('_' or '-'): "
                 "flags as booleans.");
  shrink_options.def_ro("out_dir", &gr::ShrinkRunOptions::out_dir)
      .def_ro("voxel_size", &gr::ShrinkRunOptions::voxel_size)
      .def_prop_ro("garment", [](const gr::ShrinkRunOptions& o) { return o.inputs.garment; })
      .def_prop_ro("avatar", [](const gr::ShrinkRunOptions& o) { return o.inputs.avatar; })
      .def_prop_ro("mode", [](const gr::ShrinkRunOptions& o) { return gr::to_string(o.mode); })
      .def_ro("quiet", &gr::ShrinkRunOptions::quiet);
  nb::class_<gr::ShrinkRunResult> shrink_result(m, "ShrinkResult", "How a shrink run ended.");
  bind_outcome(shrink_result);
  shrink_result.def_ro("avatar_path", &gr::ShrinkRunResult::avatar_path)
      .def_ro("report_path", &gr::ShrinkRunResult::report_path)
      .def_ro("message", &gr::ShrinkRunResult::message);
  m.def(
      "run_shrink",
      [](const gr::ShrinkRunOptions& options) { return run_stoppable(&gr::run_shrink, options); },
      nb::arg("options"),
      "Runs shrink on typed options in this process and returns its ShrinkResult.");
}

}  // namespace

NB_MODULE(_core, m) {
  m.doc() = "garment-retarget's commands and batch runner";
  nb::exception<gr::InputError>(m, "InputError", PyExc_ValueError);
  nb::exception<gr::OutputError>(m, "OutputError", PyExc_OSError);
  nb::exception<CLI::ParseError>(m, "UsageError", PyExc_ValueError);
  m.attr("version") = GR_VERSION;
  nb::dict outcomes;
  for (const gr::OutcomeRow& row : gr::outcome_table())
    outcomes[nb::int_(row.exit_code)] = row.name;
  m.attr("outcome_names") = outcomes;
  m.def("formats", &formats,
        "The mesh formats: name (a format= value), extensions, named_meshes, several_meshes, "
        "skinned.");
  m.def("parameters", &parameters,
        "Every knob a run may set: name, option (the keyword), type, unit, help, presets.");
  nb::enum_<gr::Outcome> outcome(m, "Outcome", "How a command ends; each value is its exit code.");
  for (const gr::OutcomeRow& row : gr::outcome_table()) outcome.value(row.name, row.outcome);
  nb::class_<gr::RetargetOptions>(m, "RetargetOptions",
                                  "Everything retarget can be asked, typed and checked.")
      .def_static(
          "from_json",
          [](const std::string& text) {
            return gr::retarget_options_from_json(nlohmann::json::parse(text));
          },
          nb::arg("text"),
          "The options from a JSON object of retarget's long option names ('_' or '-'): "
          "flags as booleans, repeatable options as arrays.")
      .def_ro("out_dir", &gr::RetargetOptions::out_dir)
      .def_ro("threads", &gr::RetargetOptions::threads)
      .def_ro("quiet", &gr::RetargetOptions::quiet)
      .def_prop_ro("garment", [](const gr::RetargetOptions& o) { return o.inputs.garment; })
      .def_prop_ro("avatar", [](const gr::RetargetOptions& o) { return o.inputs.avatar; })
      .def_prop_ro("quality", [](const gr::RetargetOptions& o) { return gr::to_string(o.quality); })
      .def_prop_ro("format", [](const gr::RetargetOptions& o) -> nb::object {
        if (o.format == nullptr) return nb::none();
        return nb::str(o.format->name.c_str());
      });
  nb::class_<gr::RetargetResult>(m, "RetargetResult", "How a retarget run ended.")
      .def_ro("status", &gr::RetargetResult::status)
      .def_prop_ro("exit_code",
                   [](const gr::RetargetResult& r) { return gr::to_exit_code(r.status); })
      .def_prop_ro("status_name",
                   [](const gr::RetargetResult& r) { return gr::to_string(r.status); })
      .def_ro("garment_path", &gr::RetargetResult::garment_path)
      .def_ro("report_path", &gr::RetargetResult::report_path)
      .def_ro("message", &gr::RetargetResult::message);
  m.def("run_retarget", &run_retarget, nb::arg("options"),
        "Runs retarget on typed options in this process and returns its RetargetResult.");
  bind_validate_and_shrink(m);
  m.def("run_command", &run_command, nb::arg("arguments"),
        "Runs `garment-retarget ARGUMENTS...` in this process and returns its exit code.");
  m.def("read_mesh", &read_mesh, nb::arg("path"),
        "Reads an OBJ: (V #V×3 float64, F #F×3 int32, 0-based).");
  m.def("write_mesh", &write_mesh, nb::arg("path"), nb::arg("vertices"), nb::arg("faces"),
        "Writes V (#V×3) and F (#F×3, 0-based) as an OBJ at full precision.");
  m.def("manifest_ids", &manifest_ids, nb::arg("manifest"),
        "Reads and checks a batch manifest; returns its job ids in order.");
  m.def("run_job", &run_job, nb::arg("manifest"), nb::arg("id"), nb::arg("out_dir"),
        nb::arg("program"), nb::arg("threads"),
        "Runs (or reuses) one manifest job into OUT_DIR/<id> as the batch does; returns its "
        "outcome.");
  m.def("write_summary", &write_summary, nb::arg("manifest"), nb::arg("out_dir"),
        nb::arg("reused_ids"), "Writes OUT_DIR/summary.csv from the job folders.");
  m.def("remove_interrupted_jobs", &gr::remove_interrupted_jobs, nb::arg("out_dir"),
        "Removes the temporary folders an interrupted batch left in OUT_DIR.");
  m.def("threads_per_job", &gr::threads_per_job, nb::arg("workers"),
        "Threads each of WORKERS jobs gets on this machine.");
}
