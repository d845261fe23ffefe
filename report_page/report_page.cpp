#include "report_page/report_page.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "report_page/mesh_encoding.hpp"
#include "report_page/page_assets.hpp"
#include "report_page/page_colours.hpp"
#include "report_page/page_html.hpp"
#include "report_page/view_frame.hpp"

namespace gr {

namespace {

using Json = nlohmann::ordered_json;

/// Warnings listed beside the view; the documents at the end hold them all.
constexpr std::size_t kListedWarnings = 12;

// ---- Reading the report documents -------------------------------------------------------

/// The value at a JSON pointer, or null when the document has none there.
template <typename J>
const J* find(const J& doc, const char* pointer) {
  if (!doc.is_object()) return nullptr;
  const typename J::json_pointer path(pointer);
  return doc.contains(path) ? &doc.at(path) : nullptr;
}

template <typename J>
std::optional<double> number_at(const J& doc, const char* pointer) {
  const J* v = find(doc, pointer);
  if (v && v->is_number()) return v->template get<double>();
  return std::nullopt;
}

template <typename J>
std::string text_at(const J& doc, const char* pointer) {
  const J* v = find(doc, pointer);
  if (!v) return "";
  return v->is_string() ? v->template get<std::string>() : v->dump();
}

std::string format_number(double value) { return fmt::format("{:.3g}", value); }

std::string format_length(std::optional<double> value, const std::string& units) {
  return value ? fmt::format("{:.3g} {}", *value, units) : "—";
}

std::string format_percent(std::optional<double> fraction) {
  return fraction ? fmt::format("{:.2f}%", 100.0 * *fraction) : "—";
}

// ---- The numbers beside the view ---------------------------------------------------------

struct Row {
  std::string label;
  std::string value;  ///< plain text, escaped when written
};

struct Section {
  std::string title;
  std::vector<Row> rows;
  std::string html;  ///< more content after the rows (already HTML)
};

std::string section_html(const Section& section) {
  std::string out = "<section class=\"card\"><h2>" + html_escape(section.title) + "</h2>\n";
  if (!section.rows.empty()) {
    out += "<table>\n";
    for (const Row& row : section.rows)
      out += "<tr><th>" + html_escape(row.label) + "</th><td>" + html_escape(row.value) +
             "</td></tr>\n";
    out += "</table>\n";
  }
  out += section.html;
  out += "</section>\n";
  return out;
}

/// The certificate's (or, without one, the report's) verdict as a banner.
std::string verdict_html(const ReportPageData& data) {
  const Json* certified = find(data.certificate, "/certified");
  std::optional<bool> verdict;
  if (certified && certified->is_boolean())
    verdict = certified->get<bool>();
  else if (const auto* c = find(data.report, "/certified"); c && c->is_boolean())
    verdict = c->get<bool>();
  if (!verdict) return "";
  const bool is_certificate = text_at(data.certificate, "/kind") == "certificate";
  std::string detail;
  if (const Json* counts = find(data.certificate, "/counts"))
    detail =
        fmt::format("{} garment–avatar, {} self and {} garment–garment intersecting face pairs",
                    counts->value("garment_avatar_intersections", 0),
                    counts->value("garment_self_intersections", 0),
                    counts->value("garment_garment_intersections", 0));
  const std::string headline =
      *verdict ? (is_certificate
                      ? "Certified: the written garment intersects neither the avatar nor itself"
                      : "No intersection found")
               : (is_certificate ? "NOT certified: the written garment has intersections"
                                 : "Intersections found");
  return fmt::format(
      "<div class=\"verdict {}\" id=\"gr-verdict\"><strong>{}</strong><br>{}</div>\n",
      *verdict ? "pass" : "fail", html_escape(headline), html_escape(detail));
}

/// Smallest certified garment–avatar clearance over the certificate's garments.
std::optional<double> certified_clearance(const Json& certificate) {
  const Json* garments = find(certificate, "/garments");
  if (!garments || !garments->is_array()) return std::nullopt;
  std::optional<double> smallest;
  for (const Json& g : *garments)
    if (const auto d = number_at(g, "/avatar_clearance/distance"))
      smallest = smallest ? std::min(*smallest, *d) : *d;
  return smallest;
}

std::vector<Section> retarget_sections(const ReportPageData& data) {
  const nlohmann::json& r = data.report;
  const std::string& u = data.units;
  std::vector<Section> sections;

  Section fit{"Fit", {}, ""};
  fit.rows.push_back({"mean distance to body", format_length(number_at(r, "/fit_error/mean"), u)});
  fit.rows.push_back({"95th percentile", format_length(number_at(r, "/fit_error/p95"), u)});
  if (const auto faces = number_at(r, "/modelled/fit_faces"))
    fit.rows.push_back(
        {"fit faces", fmt::format("{:.0f} of {:.0f}", *faces,
                                  number_at(r, "/modelled/garment_faces").value_or(0))});
  fit.rows.push_back(
      {"fit solve", fmt::format("{} ({:.0f} Newton steps)", text_at(r, "/fit/status"),
                                number_at(r, "/fit/newton_iterations").value_or(0))});
  sections.push_back(fit);

  Section ease{"Ease", {}, ""};
  ease.rows.push_back(
      {"fit", text_at(r, "/ease/fit") + " (source ease: " + text_at(r, "/ease/source") + ")"});
  if (number_at(r, "/ease/measured_vertices").value_or(0) > 0) {
    ease.rows.push_back(
        {"ease kept, median ratio", format_number(number_at(r, "/ease/median_ratio").value_or(0))});
    ease.rows.push_back({"vertices within 25% of their source ease",
                         format_percent(number_at(r, "/ease/within_25_percent"))});
  }
  sections.push_back(ease);

  // What the run repaired or kept of the input as given.
  const double inherited = number_at(r, "/inherited_crossings/pairs").value_or(0);
  const double split = number_at(r, "/split_non_manifold_edges/edges").value_or(0);
  const double attached = number_at(r, "/inherited_crossings/attached_pieces").value_or(0);
  const auto listed = [&](const char* pointer) {
    const nlohmann::json* list = find(r, pointer);
    return list && list->is_array() ? list->size() : std::size_t{0};
  };
  const std::size_t pierced = listed("/pierced_faces/left_out_of_contact");
  if (inherited > 0 || split > 0 || pierced > 0) {
    Section repairs{"Input as given", {}, ""};
    if (inherited > 0)
      repairs.rows.push_back(
          {"self-crossing face pairs kept (inherited)",
           fmt::format("{:.0f}, {:.0f} still crossing", inherited,
                       number_at(r, "/inherited_crossings/still_crossing").value_or(0))});
    if (attached > 0)
      repairs.rows.push_back(
          {"pieces through another piece, attached to it", fmt::format("{:.0f}", attached)});
    if (pierced > 0) {
      std::string bones;
      if (const nlohmann::json* names = find(r, "/pierced_faces/bones"); names && names->is_array())
        for (const auto& name : *names)
          if (name.is_string()) bones += (bones.empty() ? "" : ", ") + name.get<std::string>();
      repairs.rows.push_back(
          {"faces the body passes through (caps), left out of contact",
           fmt::format("{}, {} opened (not written){}", pierced, listed("/pierced_faces/opened"),
                       bones.empty() ? "" : "; bones through them: " + bones)});
    }
    if (split > 0)
      repairs.rows.push_back(
          {"edges of more than two faces, split and welded back",
           fmt::format("{:.0f} ({:.0f} vertex copies)", split,
                       number_at(r, "/split_non_manifold_edges/vertex_copies").value_or(0))});
    sections.push_back(repairs);
  }

  Section clearance{"Clearance", {}, ""};
  clearance.rows.push_back(
      {"certified minimum (exact files)", format_length(certified_clearance(data.certificate), u)});
  clearance.rows.push_back(
      {"solver's minimum distance", format_length(number_at(r, "/min_distance/avatar_units"), u)});
  sections.push_back(clearance);

  Section shape{"Shape change", {}, ""};
  if (const auto scale = number_at(r, "/shape/scale"))
    shape.rows.push_back({"scale (median edge-length ratio)", format_number(*scale)});
  shape.rows.push_back({"scale-free mean edge-length change",
                        format_percent(number_at(r, "/shape/mean_edge_change"))});
  shape.rows.push_back({"scale-free 95th-percentile edge-length change",
                        format_percent(number_at(r, "/shape/p95_edge_change"))});
  shape.rows.push_back({"area change", format_percent(number_at(r, "/shape/area_change"))});
  shape.rows.push_back({"largest boundary-loop displacement (of the diagonal)",
                        format_percent(number_at(r, "/shape/loop_displacement"))});
  if (const auto e = number_at(r, "/shape/surface_energy_per_area"))
    shape.rows.push_back({"surface energy per area", format_number(*e)});
  if (const auto* loops = find(r, "/position/loop_offsets");
      loops && loops->is_array() && !loops->empty()) {
    double worst = 0.0;
    for (const auto& v : *loops) worst = std::max(worst, v.get<double>());
    shape.rows.push_back(
        {"boundary loops off their place",
         fmt::format("{} loops, worst {:.2f}% of its bone", loops->size(), 100.0 * worst)});
  }
  sections.push_back(shape);

  Section times{"Stage times", {}, ""};
  for (const char* stage :
       {"read", "normalize", "shrink", "inflate", "fit", "write", "certify", "total"})
    if (const auto s = number_at(r, (std::string("/seconds/") + stage).c_str()))
      times.rows.push_back({stage, fmt::format("{:.2f} s", *s)});
  sections.push_back(times);

  Section run{"Run", {}, ""};
  run.rows.push_back({"quality", text_at(r, "/quality")});
  run.rows.push_back(
      {"shrink", fmt::format("{} (depth {})", text_at(r, "/shrink/mode"),
                             format_number(number_at(r, "/shrink/depth").value_or(0)))});
  run.rows.push_back(
      {"inflation",
       fmt::format("{} ({:.0f} rounds, {:.0f} resets, {:.0f} Newton steps)",
                   text_at(r, "/inflate/status"), number_at(r, "/inflate/al_rounds").value_or(0),
                   number_at(r, "/inflate/resets").value_or(0),
                   number_at(r, "/inflate/newton_iterations").value_or(0))});
  if (const auto* terms = find(r, "/modelled/terms"); terms && terms->is_array()) {
    std::string list;
    for (const auto& t : *terms) list += (list.empty() ? "" : ", ") + t.get<std::string>();
    run.rows.push_back({"terms", list});
  }
  run.rows.push_back(
      {"avatar faces modelled",
       fmt::format("{:.0f} of {:.0f}", number_at(r, "/modelled/avatar_faces_modelled").value_or(0),
                   number_at(r, "/modelled/avatar_faces_total").value_or(0))});
  run.rows.push_back({"self-contact", text_at(r, "/modelled/self_contact_where")});
  if (const auto m = number_at(r, "/peak_memory_mb"))
    run.rows.push_back({"peak memory", fmt::format("{:.0f} MB", *m)});
  sections.push_back(run);
  return sections;
}

/// Per garment of a validation report or certificate: its counts and clearance.
std::vector<Section> validation_sections(const ReportPageData& data) {
  std::vector<Section> sections;
  const Json* garments = find(data.certificate, "/garments");
  if (!garments || !garments->is_array()) return sections;
  for (const Json& g : *garments) {
    Section s{"Garment " + text_at(g, "/path"), {}, ""};
    s.rows.push_back({"intersecting the avatar",
                      fmt::format("{:.0f} face pairs",
                                  number_at(g, "/avatar_intersections/count").value_or(0))});
    s.rows.push_back(
        {"intersecting itself",
         fmt::format("{:.0f} face pairs", number_at(g, "/self_intersections/count").value_or(0))});
    s.rows.push_back({"degenerate faces",
                      fmt::format("{:.0f}", number_at(g, "/degenerate_faces/count").value_or(0))});
    s.rows.push_back({"clearance to the avatar",
                      format_length(number_at(g, "/avatar_clearance/distance"), data.units)});
    if (const auto near = number_at(g, "/near_vertices/count"))
      s.rows.push_back({"vertices nearer than " +
                            format_number(number_at(g, "/near_vertices/threshold").value_or(0)),
                        format_number(*near)});
    sections.push_back(s);
  }
  return sections;
}

/// The report's warnings and the certificate's errors and warnings.
Section warnings_section(const ReportPageData& data) {
  std::vector<std::string> items;
  if (const auto* w = find(data.report, "/warnings"); w && w->is_array())
    for (const auto& text : *w) items.push_back(text.get<std::string>());
  if (const Json* messages = find(data.certificate, "/issues/messages");
      messages && messages->is_array())
    for (const Json& m : *messages) {
      const std::string severity = m.value("severity", "");
      if (severity == "error" || severity == "warning")
        items.push_back(severity + " " + m.value("code", "") + ": " + m.value("message", ""));
    }
  Section s{"Warnings", {}, ""};
  if (items.empty()) {
    s.html = "<p class=\"none\">none</p>\n";
    return s;
  }
  s.html = "<ul class=\"warnings\">\n";
  for (std::size_t i = 0; i < std::min(items.size(), kListedWarnings); ++i)
    s.html += "<li>" + html_escape(items[i]) + "</li>\n";
  if (items.size() > kListedWarnings)
    s.html += fmt::format("<li>and {} more in the documents below</li>\n",
                          items.size() - kListedWarnings);
  s.html += "</ul>\n";
  return s;
}

/// Both documents in full, folded.
std::string documents_html(const ReportPageData& data) {
  std::string out;
  auto add = [&](const char* name, const std::string& text) {
    out += fmt::format("<details class=\"document\"><summary>{}</summary><pre>{}</pre></details>\n",
                       name, html_escape(text));
  };
  if (!data.report.is_null()) add("report.json", data.report.dump(2));
  if (!data.certificate.is_null())
    add(text_at(data.certificate, "/kind") == "certificate" ? "certificate.json"
                                                            : "validation report",
        data.certificate.dump(2));
  return out;
}

// ---- The view ------------------------------------------------------------------------

bool has_no_fit_faces(const ReportPageData& data) {
  for (const PageGarment& g : data.garments)
    if (std::find(g.no_fit.begin(), g.no_fit.end(), true) != g.no_fit.end()) return true;
  return false;
}

bool has_ease(const ReportPageData& data) {
  for (const PageGarment& g : data.garments)
    for (const GarmentShape& s : g.shapes)
      if (!s.ease_ratio.empty()) return true;
  return false;
}

/// The ease map's legend, shown in place of the distance legend in the ease colour mode.
std::string ease_legend_html() {
  std::string gradient;
  for (const HeatStop& s : ease_stops())
    gradient += fmt::format(", rgb({},{},{}) {:.0f}%", s.colour.r, s.colour.g, s.colour.b,
                            100.0 * s.position);
  std::string out =
      "<div class=\"legend\" id=\"gr-legend-ease\" hidden>\n<div class=\"legend-title\">ease "
      "kept: distance to the body against the source's, at the garment's scale</div>\n";
  out += fmt::format(
      "<div class=\"gradient\" style=\"background: linear-gradient(to right{})\"></div>\n",
      gradient);
  out +=
      "<div class=\"ticks\"><span>0 (on the body)</span><span>1 (as made)</span><span>≥ "
      "2</span></div>\n";
  out += fmt::format(
      "<div class=\"swatches\"><span class=\"swatch\" id=\"gr-swatch-unmeasured\"><i "
      "style=\"background: rgb({},{},{})\"></i>not measured (no-fit, or no source "
      "ease)</span><span class=\"swatch\"><i style=\"background: rgb({},{},{})\"></i>intersecting "
      "or marked</span></div>\n</div>\n",
      kUnmeasuredEaseColour.r, kUnmeasuredEaseColour.g, kUnmeasuredEaseColour.b, kMarkedColour.r,
      kMarkedColour.g, kMarkedColour.b);
  return out;
}

bool has_shape_toggle(const ReportPageData& data) {
  for (const PageGarment& g : data.garments)
    if (g.shapes.size() > 1) return true;
  return false;
}

/// The heat map's legend: the gradient with its distances, and the other colours.
std::string legend_html(const ReportPageData& data, double heat_range) {
  std::string gradient;
  for (const HeatStop& s : heat_stops())
    gradient += fmt::format(", rgb({},{},{}) {:.0f}%", s.colour.r, s.colour.g, s.colour.b,
                            100.0 * s.position);
  auto swatch = [](Rgb8 c, const char* label, const char* id) {
    return fmt::format(
        "<span class=\"swatch\" id=\"{}\"><i style=\"background: rgb({},{},{})\"></i>{}</span>", id,
        c.r, c.g, c.b, label);
  };
  std::string out =
      "<div class=\"legend\" id=\"gr-legend\">\n<div class=\"legend-title\">distance to the "
      "body</div>\n";
  out += fmt::format(
      "<div class=\"gradient\" style=\"background: linear-gradient(to right{})\"></div>\n",
      gradient);
  out += fmt::format(
      "<div class=\"ticks\"><span>0</span><span>{}</span><span>≥ {} {}</span></div>\n",
      format_number(0.5 * heat_range), format_number(heat_range), html_escape(data.units));
  out += "<div class=\"swatches\">";
  if (has_no_fit_faces(data))
    out += fmt::format(
        "<span class=\"swatch\" id=\"gr-swatch-nofit\"><i style=\"background: "
        "repeating-linear-gradient("
        "135deg, rgb({0},{1},{2}) 0 2px, #fff 2px 5px)\"></i>no-fit (striped: hangs free)</span>",
        kNoFitColour.r, kNoFitColour.g, kNoFitColour.b);
  out += swatch(kMarkedColour, "intersecting or marked", "gr-swatch-marked");
  out += swatch(kAvatarColour, "avatar", "gr-swatch-avatar");
  out += "</div>\n</div>\n";
  return out;
}

std::string toolbar_html(const ReportPageData& data) {
  std::string out = "<div class=\"toolbar\">\n";
  const PageGarment* toggled = nullptr;
  for (const PageGarment& g : data.garments)
    if (g.shapes.size() > 1 && !toggled) toggled = &g;
  if (toggled) {
    out += "<span class=\"shapes\" role=\"group\" aria-label=\"garment shape\">";
    for (std::size_t i = 0; i < toggled->shapes.size(); ++i)
      out += fmt::format(
          "<button type=\"button\" class=\"shape-button\" data-shape=\"{}\" "
          "id=\"gr-shape-{}\">{}</button>",
          i, i, html_escape(toggled->shapes[i].label));
    out += "</span>\n";
  }
  if (has_no_fit_faces(data))
    out += "<label><input type=\"checkbox\" id=\"gr-nofit\" checked> no-fit region</label>\n";
  if (has_ease(data))
    out += "<label><input type=\"checkbox\" id=\"gr-ease\"> colour by ease kept</label>\n";
  // An outfit: each garment (layer) can be hidden to see the one under it.
  if (data.garments.size() > 1)
    for (std::size_t g = 0; g < data.garments.size(); ++g)
      out += fmt::format(
          "<label><input type=\"checkbox\" class=\"garment-toggle\" data-garment=\"{}\" "
          "id=\"gr-garment-{}\" checked> {}</label>\n",
          g, g, html_escape(data.garments[g].name));
  out +=
      "<label><input type=\"checkbox\" id=\"gr-body\" checked> avatar</label>\n"
      "<label><input type=\"checkbox\" id=\"gr-seethrough\"> see-through avatar</label>\n"
      "<button type=\"button\" id=\"gr-reset\">front view</button>\n</div>\n";
  return out;
}

void require(bool condition, const std::string& what) {
  if (!condition) throw std::invalid_argument("report page: " + what);
}

std::vector<int> face_list(const std::vector<bool>& flags) {
  std::vector<int> faces;
  for (std::size_t f = 0; f < flags.size(); ++f)
    if (flags[f]) faces.push_back(static_cast<int>(f));
  return faces;
}

}  // namespace

nlohmann::ordered_json report_page_scene(const ReportPageData& data) {
  const double heat_range = page_heat_range(data);
  Json garments = Json::array();
  for (const PageGarment& g : data.garments) {
    const Eigen::Index face_count = g.faces.rows();
    require(!g.shapes.empty(), "garment '" + g.name + "' has no shape");
    require(g.no_fit.empty() || static_cast<Eigen::Index>(g.no_fit.size()) == face_count,
            "garment '" + g.name + "' has a no-fit flag count other than its face count");
    Json shapes = Json::array();
    for (const GarmentShape& s : g.shapes) {
      const Eigen::Index n = s.vertices.rows();
      require(static_cast<Eigen::Index>(s.distance.size()) == n,
              "shape '" + s.label + "' needs one distance per vertex");
      require(face_count == 0 || (g.faces.minCoeff() >= 0 && g.faces.maxCoeff() < n),
              "garment '" + g.name + "' has a face index outside shape '" + s.label + "'");
      for (const int f : s.marked_faces)
        require(f >= 0 && f < face_count, "shape '" + s.label + "' marks a face it does not have");
      require(s.ease_ratio.empty() || static_cast<Eigen::Index>(s.ease_ratio.size()) == n,
              "shape '" + s.label + "' needs one ease ratio per vertex, or none");
      Json shape = {{"label", s.label},
                    {"positions", encode_positions(s.vertices)},
                    {"distance", encode_unit_values(s.distance)},
                    {"marked", s.marked_faces}};
      if (!s.ease_ratio.empty()) {
        // The map saturates at 2; unmeasured vertices go as a list of their own.
        std::vector<double> ratio(s.ease_ratio.size());
        std::vector<int> unmeasured;
        for (std::size_t v = 0; v < ratio.size(); ++v) {
          const double r = s.ease_ratio[v];
          ratio[v] = std::isfinite(r) ? std::clamp(r, 0.0, 2.0) : 0.0;
          if (!std::isfinite(r)) unmeasured.push_back(static_cast<int>(v));
        }
        shape["ease_ratio"] = encode_unit_values(ratio);
        shape["ease_unmeasured"] = unmeasured;
      }
      shapes.push_back(std::move(shape));
    }
    garments.push_back({{"name", g.name},
                        {"faces", encode_indices(g.faces)},
                        {"no_fit", face_list(g.no_fit)},
                        {"shapes", shapes}});
  }
  const Eigen::Index avatar_vertices = data.avatar.vertices.rows();
  require(data.avatar.faces.rows() == 0 ||
              (data.avatar.faces.minCoeff() >= 0 && data.avatar.faces.maxCoeff() < avatar_vertices),
          "avatar face index out of range");
  return Json{{"units", data.units},
              {"heat_range", heat_range},
              {"colours", page_colours_json()},
              {"view", to_json(guess_view_frame(data.avatar.vertices))},
              {"avatar",
               {{"positions", encode_positions(data.avatar.vertices)},
                {"faces", encode_indices(data.avatar.faces)}}},
              {"garments", garments}};
}

std::string report_page_html(const ReportPageData& data) {
  const Json scene = report_page_scene(data);
  const double heat_range = scene["heat_range"].get<double>();

  std::string body = "<header><h1>" + html_escape(data.title) + "</h1>";
  if (!data.subtitle.empty())
    body += "<p class=\"subtitle\">" + html_escape(data.subtitle) + "</p>";
  body += "</header>\n<main class=\"report\">\n<section class=\"view\">\n";
  body += toolbar_html(data);
  body +=
      "<div class=\"canvas-box\" id=\"gr-view\"><noscript>The 3D view needs "
      "JavaScript.</noscript></div>\n";
  body += legend_html(data, heat_range);
  if (has_ease(data)) body += ease_legend_html();
  body += std::string("<p class=\"hint\">Drag to orbit, scroll to zoom, right-drag to pan") +
          (has_shape_toggle(data) ? "; T toggles the garment's shape" : "") + ".</p>\n";
  body += "</section>\n<aside class=\"numbers\">\n";
  body += verdict_html(data);
  std::vector<Section> sections =
      data.report.is_null() ? validation_sections(data) : retarget_sections(data);
  sections.push_back(warnings_section(data));
  for (const Section& s : sections) body += section_html(s);
  body += documents_html(data);
  body += "</aside>\n</main>\n<footer>\n";
  body += fmt::format(
      "<details class=\"licence\"><summary>The 3D view uses three.js {} (MIT "
      "licence)</summary><pre>{}</pre></details>\n",
      html_escape(three_version()), html_escape(three_license()));
  body += "</footer>\n";
  body +=
      "<script type=\"application/json\" id=\"gr-scene\">" + json_for_script(scene) + "</script>\n";
  body += fmt::format(
      "<script>\n/* three.js {} (MIT licence, text in the footer), bundled with the report's "
      "viewer */\n",
      three_version());
  body += viewer_script();
  body += "\n</script>\n";
  return html_document(data.title, body);
}

void write_report_page(const std::string& path, const ReportPageData& data) {
  write_page_file(path, report_page_html(data));
}

}  // namespace gr
