#include "retarget/retarget_options_json.hpp"

#include <cmath>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>

#include "core/io/formats/mesh_formats.hpp"

namespace gr {

namespace {

// Each struct's fields are listed once, in fields(); the writer and the reader visit them.

template <typename V>
void fields(GarmentPaths& p, V& v) {
  v("garment", p.garment);
  v("garment_mesh", p.garment_mesh);
  v("no_fit", p.no_fit);
  v("source_skeleton", p.source_skeleton);
  v("source_body", p.source_body);
}

template <typename V>
void fields(ScenePaths& p, V& v) {
  v("garment", p.garment);
  v("avatar", p.avatar);
  v("source_skeleton", p.source_skeleton);
  v("target_skeleton", p.target_skeleton);
  v("skin_weights", p.skin_weights);
  v("no_fit", p.no_fit);
  v("garment_mesh", p.garment_mesh);
  v("avatar_meshes", p.avatar_meshes);
  v("joint_map", p.joint_map);
  v("source_body", p.source_body);
  v("source_body_meshes", p.source_body_meshes);
  v("more_garments", p.more_garments);
}

template <typename V>
void fields(BindingOptions& o, V& v) {
  // The method follows InferenceOptions::binding; the interrupter is the run's.
  v("resolution", o.resolution);
  v("falloff", o.falloff);
  v("distance_ratio", o.distance_ratio);
  v("max_influences", o.max_influences);
  v("root_joint", o.root_joint);
  v("end_angle_degrees", o.end_angle_degrees);
  v("end_length", o.end_length);
}

template <typename V>
void fields(NoFitOptions& o, V& v) {
  v("body_distance_edges", o.body_distance_edges);
  v("snug_percentile", o.snug_percentile);
  v("min_region_share", o.min_region_share);
  v("hip_offset", o.hip_offset);
  v("end_margin", o.end_margin);
  v("root_joint", o.root_joint);
  v("end_angle_degrees", o.end_angle_degrees);
}

template <typename V>
void fields(InferenceOptions& o, V& v) {
  v("binding", o.binding);
  v("binding_options", o.binding_options);
  v("no_fit", o.no_fit);
}

template <typename V>
void fields(ShapeThresholds& t, V& v) {
  v("min_scale", t.min_scale);
  v("max_scale", t.max_scale);
  v("mean_edge_change", t.mean_edge_change);
  v("p95_edge_change", t.p95_edge_change);
  v("area_change", t.area_change);
  v("loop_displacement", t.loop_displacement);
  v("enabled", t.enabled);
}

template <typename V>
void fields(SkinTransferOptions& o, V& v) {
  v("max_distance", o.max_distance);
  v("max_angle_degrees", o.max_angle_degrees);
  v("max_influences", o.max_influences);
}

template <typename V>
void fields(RunLimits& l, V& v) {
  v("max_input_mb", l.max_input_mb);
  v("max_faces", l.max_faces);
  v("max_memory_mb", l.max_memory_mb);
  v("timeout_seconds", l.timeout_seconds);
}

template <typename V>
void fields(RetargetOptions& o, V& v) {
  v("inputs", o.inputs);
  v("out_dir", o.out_dir);
  v("skirt", o.skirt);
  v("skirt_layers", o.skirt_layers);
  v("shrink_mode", o.shrink_mode);
  v("quality", o.quality);
  v("fit_mode", o.fit_mode);
  v("overrides", o.overrides);
  v("inference", o.inference);
  v("shape_thresholds", o.shape_thresholds);
  v("threads", o.threads);
  v("frames", o.frames);
  v("png", o.png);
  v("quiet", o.quiet);
  v("format", o.format);
  v("split", o.split);
  v("write_avatar", o.write_avatar);
  v("layer_order", o.layer_order);
  v("skin_transfer", o.skin_transfer);
  v("limits", o.limits);
  v("allow_external_assets", o.allow_external_assets);
  v("write_in_place", o.write_in_place);
  v("open_pierced_faces", o.open_pierced_faces);
  v("animations", o.animations);
  v("fps", o.fps);
  v("pose", o.pose);
  v("pose_skinning", o.pose_skinning);
  v("write_posed", o.write_posed);
}

const char* name_of(BindingChoice choice) { return to_string(choice); }
const char* name_of(ShrinkMode mode) { return to_string(mode); }
const char* name_of(Quality quality) { return to_string(quality); }
const char* name_of(FitMode mode) { return to_string(mode); }
const char* name_of(PoseMode mode) { return to_string(mode); }
const char* name_of(SkinningMethod method) { return to_string(method); }
void parse_name(const std::string& name, BindingChoice& out) { out = parse_binding_choice(name); }
void parse_name(const std::string& name, ShrinkMode& out) { out = parse_shrink_mode(name); }
void parse_name(const std::string& name, Quality& out) { out = parse_quality(name); }
void parse_name(const std::string& name, FitMode& out) { out = parse_fit_mode(name); }
void parse_name(const std::string& name, PoseMode& out) { out = parse_pose_mode(name); }
void parse_name(const std::string& name, SkinningMethod& out) { out = parse_skinning_method(name); }

// Writing.

template <typename S>
nlohmann::json encode_fields(const S& value);

nlohmann::json encode(double value) {
  if (std::isfinite(value)) return value;
  return std::isnan(value) ? "nan" : value > 0 ? "inf" : "-inf";
}
nlohmann::json encode(int value) { return value; }
nlohmann::json encode(bool value) { return value; }
nlohmann::json encode(const std::string& value) { return value; }
nlohmann::json encode(const MeshFormat* format) {
  return format ? nlohmann::json(format->name) : nlohmann::json(nullptr);
}
nlohmann::json encode(const ParameterOverrides& overrides) {
  nlohmann::json object = nlohmann::json::object();
  for (const auto& [name, value] : overrides.values()) object[name] = encode(value);
  return object;
}
template <typename E, typename = decltype(name_of(std::declval<E>()))>
nlohmann::json encode(E value) {
  return name_of(value);
}
nlohmann::json encode(const GarmentPaths& value) { return encode_fields(value); }
nlohmann::json encode(const ScenePaths& value) { return encode_fields(value); }
nlohmann::json encode(const BindingOptions& value) { return encode_fields(value); }
nlohmann::json encode(const NoFitOptions& value) { return encode_fields(value); }
nlohmann::json encode(const InferenceOptions& value) { return encode_fields(value); }
nlohmann::json encode(const ShapeThresholds& value) { return encode_fields(value); }
nlohmann::json encode(const SkinTransferOptions& value) { return encode_fields(value); }
nlohmann::json encode(const RunLimits& value) { return encode_fields(value); }
template <typename T>
nlohmann::json encode(const std::optional<T>& value) {
  return value ? encode(*value) : nlohmann::json(nullptr);
}
template <typename T>
nlohmann::json encode(const std::vector<T>& values) {
  nlohmann::json array = nlohmann::json::array();
  for (const T& value : values) array.push_back(encode(value));
  return array;
}

struct Writer {
  nlohmann::json& object;
  template <typename T>
  void operator()(const char* name, const T& value) {
    object[name] = encode(value);
  }
};

template <typename S>
nlohmann::json encode_fields(const S& value) {
  nlohmann::json object = nlohmann::json::object();
  Writer writer{object};
  fields(const_cast<S&>(value), writer);  // the writer only reads
  return object;
}

// Reading: every field must be there, of its type, and nothing else.

std::invalid_argument mistyped(const std::string& where, const char* wanted) {
  return std::invalid_argument(fmt::format("retarget options: \"{}\" must be {}", where, wanted));
}

template <typename S>
void decode_fields(const nlohmann::json& object, const std::string& where, S& value);

void decode(const nlohmann::json& j, const std::string& where, double& out) {
  if (j.is_number()) {
    out = j.get<double>();
  } else if (j.is_string() && (j == "inf" || j == "-inf" || j == "nan")) {
    out = std::stod(j.get<std::string>());
  } else {
    throw mistyped(where, "a number");
  }
}
void decode(const nlohmann::json& j, const std::string& where, int& out) {
  if (!j.is_number_integer()) throw mistyped(where, "an integer");
  out = j.get<int>();
}
void decode(const nlohmann::json& j, const std::string& where, bool& out) {
  if (!j.is_boolean()) throw mistyped(where, "a boolean");
  out = j.get<bool>();
}
void decode(const nlohmann::json& j, const std::string& where, std::string& out) {
  if (!j.is_string()) throw mistyped(where, "a text");
  out = j.get<std::string>();
}
void decode(const nlohmann::json& j, const std::string& where, const MeshFormat*& out) {
  if (j.is_null()) {
    out = nullptr;
    return;
  }
  if (!j.is_string()) throw mistyped(where, "a format name or null");
  out = &mesh_format_named(j.get<std::string>());
}
void decode(const nlohmann::json& j, const std::string& where, ParameterOverrides& out) {
  if (!j.is_object()) throw mistyped(where, "an object");
  for (const auto& [name, value] : j.items()) {
    double number = 0.0;
    decode(value, where + "." + name, number);
    out.set(name, number);
  }
}
template <typename E, typename = decltype(name_of(std::declval<E>()))>
void decode(const nlohmann::json& j, const std::string& where, E& out) {
  if (!j.is_string()) throw mistyped(where, "a name");
  parse_name(j.get<std::string>(), out);
}
void decode(const nlohmann::json& j, const std::string& w, GarmentPaths& out) {
  decode_fields(j, w, out);
}
void decode(const nlohmann::json& j, const std::string& w, ScenePaths& out) {
  decode_fields(j, w, out);
}
void decode(const nlohmann::json& j, const std::string& w, BindingOptions& out) {
  decode_fields(j, w, out);
}
void decode(const nlohmann::json& j, const std::string& w, NoFitOptions& out) {
  decode_fields(j, w, out);
}
void decode(const nlohmann::json& j, const std::string& w, InferenceOptions& out) {
  decode_fields(j, w, out);
}
void decode(const nlohmann::json& j, const std::string& w, ShapeThresholds& out) {
  decode_fields(j, w, out);
}
void decode(const nlohmann::json& j, const std::string& w, SkinTransferOptions& out) {
  decode_fields(j, w, out);
}
void decode(const nlohmann::json& j, const std::string& w, RunLimits& out) {
  decode_fields(j, w, out);
}
template <typename T>
void decode(const nlohmann::json& j, const std::string& where, std::optional<T>& out) {
  if (j.is_null()) {
    out.reset();
    return;
  }
  T value{};
  decode(j, where, value);
  out = value;
}
template <typename T>
void decode(const nlohmann::json& j, const std::string& where, std::vector<T>& out) {
  if (!j.is_array()) throw mistyped(where, "an array");
  out.clear();
  for (std::size_t i = 0; i < j.size(); ++i) {
    T value{};
    decode(j[i], fmt::format("{}[{}]", where, i), value);
    out.push_back(std::move(value));
  }
}

struct Reader {
  const nlohmann::json& object;
  const std::string& where;
  std::size_t fields_read = 0;
  template <typename T>
  void operator()(const char* name, T& value) {
    const std::string at = where.empty() ? name : where + "." + name;
    const auto found = object.find(name);
    if (found == object.end())
      throw std::invalid_argument(fmt::format("retarget options: \"{}\" is missing", at));
    decode(*found, at, value);
    ++fields_read;
  }
};

template <typename S>
void decode_fields(const nlohmann::json& object, const std::string& where, S& value) {
  if (!object.is_object()) throw mistyped(where.empty() ? "the options" : where, "an object");
  Reader reader{object, where};
  fields(value, reader);
  if (reader.fields_read != object.size())
    throw std::invalid_argument(
        fmt::format("retarget options: \"{}\" has {} fields, not the {} this program knows",
                    where.empty() ? "the options" : where, object.size(), reader.fields_read));
}

}  // namespace

nlohmann::json retarget_options_to_json(const RetargetOptions& options) {
  return encode_fields(options);
}

RetargetOptions retarget_options_from_typed_json(const nlohmann::json& object) {
  RetargetOptions options;
  decode_fields(object, "", options);
  return options;
}

}  // namespace gr
