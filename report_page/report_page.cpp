#include "report_page/report_page.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "report_page/mesh_encoding.hpp"
#include "report_page/page_animation.hpp"
#include "report_page/page_assets.hpp"
#include "report_page/page_colours.hpp"
#include "report_page/page_html.hpp"
#include "report_page/page_report.hpp"
#include "report_page/view_frame.hpp"

namespace gr {

namespace {

using Json = nlohmann::ordered_json;

/// Warnings listed beside the view; the documents at the end hold them all.
constexpr std::size_t kListedWarnings = 12;

std::string format_number(double value) { return fmt::format("{:.3g}", value); }

std::string format_length(std::optional<double> value, const std::string& units) {
  return value ? fmt::format("{:.3g} {}", *value, units) : "—";
}

std::string format_percent(std::optional<double> fraction) {
  return fraction ? fmt::format("{:.2f}%", 100.0 * *fraction) : "—";
}

/// `items` joined by ", ".
std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
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
std::string verdict_html(const PageReport& page) {
  const CertificatePageReport certificate = page.certificate.value_or(CertificatePageReport{});
  std::optional<bool> verdict = certificate.certified;
  if (!verdict && page.run) verdict = page.run->certified;
  if (!verdict) return "";
  const bool is_certificate = certificate.kind == "certificate";
  std::string detail;
  if (const auto& counts = certificate.counts)
    detail =
        fmt::format("{} garment–avatar, {} self and {} garment–garment intersecting face pairs",
                    counts->garment_avatar_intersections, counts->garment_self_intersections,
                    counts->garment_garment_intersections);
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
std::optional<double> certified_clearance(const std::optional<CertificatePageReport>& certificate) {
  if (!certificate) return std::nullopt;
  std::optional<double> smallest;
  for (const CertificateGarment& g : certificate->garments)
    if (const auto d = g.avatar_clearance) smallest = smallest ? std::min(*smallest, *d) : *d;
  return smallest;
}

/// What the run repaired or kept of the input as given; no section when nothing.
std::optional<Section> repairs_section(const RunPageReport& r) {
  const auto untangle = r.untangle.value_or(ReportUntangle{});
  const auto inherited = r.inherited_crossings.value_or(ReportInheritedCrossings{});
  const auto split = r.split_non_manifold_edges.value_or(ReportSplitEdges{});
  const auto pierced = r.pierced_faces.value_or(ReportPiercedFaces{});
  if (untangle.pairs <= 0 && inherited.pairs <= 0 && split.edges <= 0 &&
      pierced.left_out_of_contact.empty())
    return std::nullopt;
  Section repairs{"Input as given", {}, ""};
  if (untangle.pairs > 0)
    repairs.rows.push_back(
        {"self-crossing face pairs pushed apart before the solve",
         fmt::format("{} of {}, {} crossing after it; largest move {:.3g} of the diagonal",
                     untangle.resolved, untangle.pairs, untangle.remaining,
                     untangle.max_displacement.value_or(0.0))});
  if (inherited.pairs > 0)
    repairs.rows.push_back(
        {"self-crossing face pairs kept (inherited)",
         fmt::format("{}, {} still crossing", inherited.pairs, inherited.still_crossing)});
  if (inherited.attached_pieces > 0)
    repairs.rows.push_back({"pieces through another piece, attached to it",
                            fmt::format("{}", inherited.attached_pieces)});
  if (!pierced.left_out_of_contact.empty()) {
    const std::string bones = joined(pierced.bones);
    repairs.rows.push_back({"faces the body passes through (caps), left out of contact",
                            fmt::format("{}, {} opened (not written){}",
                                        pierced.left_out_of_contact.size(), pierced.opened.size(),
                                        bones.empty() ? "" : "; bones through them: " + bones)});
  }
  if (split.edges > 0)
    repairs.rows.push_back(
        {"edges of more than two faces, split and welded back",
         fmt::format("{} ({} vertex copies)", split.edges, split.vertex_copies)});
  return repairs;
}

std::vector<Section> retarget_sections(const RunPageReport& r,
                                       const std::optional<CertificatePageReport>& certificate,
                                       const std::string& u) {
  std::vector<Section> sections;
  const auto fit_error = r.fit_error.value_or(ReportFitError{});
  const auto fit_solve = r.fit.value_or(ReportFitSolve{});
  Section fit{"Fit", {}, ""};
  fit.rows.push_back({"mean distance to body", format_length(fit_error.mean, u)});
  fit.rows.push_back({"95th percentile", format_length(fit_error.p95, u)});
  if (r.modelled)
    fit.rows.push_back(
        {"fit faces", fmt::format("{} of {}", r.modelled->fit_faces, r.modelled->garment_faces)});
  fit.rows.push_back({"fit solve", fmt::format("{} ({} Newton steps)", fit_solve.status,
                                               fit_solve.newton_iterations)});
  sections.push_back(fit);

  const auto ease_kept = r.ease.value_or(ReportEase{});
  Section ease{"Ease", {}, ""};
  ease.rows.push_back({"fit", ease_kept.fit + " (source ease: " + ease_kept.source + ")"});
  if (ease_kept.measured_vertices > 0) {
    ease.rows.push_back(
        {"ease kept, median ratio", format_number(ease_kept.median_ratio.value_or(0))});
    ease.rows.push_back(
        {"vertices within 25% of their source ease", format_percent(ease_kept.within_25_percent)});
  }
  sections.push_back(ease);

  if (auto repairs = repairs_section(r)) sections.push_back(std::move(*repairs));

  Section clearance{"Clearance", {}, ""};
  clearance.rows.push_back(
      {"certified minimum (exact files)", format_length(certified_clearance(certificate), u)});
  clearance.rows.push_back({"solver's minimum distance", format_length(r.min_distance, u)});
  sections.push_back(clearance);

  const auto change = r.shape.value_or(ReportShape{});
  Section shape{"Shape change", {}, ""};
  if (change.scale)
    shape.rows.push_back({"scale (median edge-length ratio)", format_number(*change.scale)});
  shape.rows.push_back(
      {"scale-free mean edge-length change", format_percent(change.mean_edge_change)});
  shape.rows.push_back(
      {"scale-free 95th-percentile edge-length change", format_percent(change.p95_edge_change)});
  shape.rows.push_back({"area change", format_percent(change.area_change)});
  shape.rows.push_back({"largest boundary-loop displacement (of the diagonal)",
                        format_percent(change.loop_displacement)});
  if (change.surface_energy_per_area)
    shape.rows.push_back(
        {"surface energy per area", format_number(*change.surface_energy_per_area)});
  if (!r.loop_offsets.empty()) {
    double worst = 0.0;
    for (const double offset : r.loop_offsets) worst = std::max(worst, offset);
    shape.rows.push_back(
        {"boundary loops off their place",
         fmt::format("{} loops, worst {:.2f}% of its bone", r.loop_offsets.size(), 100.0 * worst)});
  }
  sections.push_back(shape);

  Section times{"Stage times", {}, ""};
  for (const ReportStageTime& t : r.seconds)
    if (t.seconds) times.rows.push_back({t.stage, fmt::format("{:.2f} s", *t.seconds)});
  sections.push_back(times);

  const auto shrink = r.shrink.value_or(ReportShrink{});
  const auto inflate = r.inflate.value_or(ReportInflate{});
  const auto modelled = r.modelled.value_or(ReportModelled{});
  Section run{"Run", {}, ""};
  run.rows.push_back({"quality", r.quality});
  run.rows.push_back({"shrink", fmt::format("{} (depth {})", shrink.mode,
                                            format_number(shrink.depth.value_or(0)))});
  run.rows.push_back(
      {"inflation", fmt::format("{} ({} rounds, {} resets, {} Newton steps)", inflate.status,
                                inflate.al_rounds, inflate.resets, inflate.newton_iterations)});
  if (r.modelled) run.rows.push_back({"terms", joined(modelled.terms)});
  run.rows.push_back(
      {"avatar faces modelled",
       fmt::format("{} of {}", modelled.avatar_faces_modelled, modelled.avatar_faces_total)});
  run.rows.push_back({"self-contact", modelled.self_contact_where});
  if (r.peak_memory_mb)
    run.rows.push_back({"peak memory", fmt::format("{:.0f} MB", *r.peak_memory_mb)});
  sections.push_back(run);
  return sections;
}

/// Per garment of a validation report or certificate: its counts and clearance.
std::vector<Section> validation_sections(const std::optional<CertificatePageReport>& certificate,
                                         const std::string& units) {
  std::vector<Section> sections;
  if (!certificate) return sections;
  for (const CertificateGarment& g : certificate->garments) {
    Section s{"Garment " + g.path, {}, ""};
    s.rows.push_back(
        {"intersecting the avatar", fmt::format("{} face pairs", g.avatar_intersections)});
    s.rows.push_back({"intersecting itself", fmt::format("{} face pairs", g.self_intersections)});
    s.rows.push_back({"degenerate faces", fmt::format("{}", g.degenerate_faces)});
    s.rows.push_back({"clearance to the avatar", format_length(g.avatar_clearance, units)});
    if (const auto& near = g.near_vertices)
      s.rows.push_back({"vertices nearer than " + format_number(near->threshold.value_or(0)),
                        format_number(near->count)});
    sections.push_back(s);
  }
  return sections;
}

/// The report's warnings and the certificate's errors and warnings.
Section warnings_section(const PageReport& page) {
  std::vector<std::string> items;
  if (page.run) items = page.run->warnings;
  if (page.certificate)
    for (const CertificateMessage& m : page.certificate->messages)
      if (m.severity == "error" || m.severity == "warning")
        items.push_back(m.severity + " " + m.code + ": " + m.message);
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
std::string documents_html(const ReportPageData& data, const PageReport& page) {
  std::string out;
  auto add = [&](const char* name, const std::string& text) {
    out += fmt::format("<details class=\"document\"><summary>{}</summary><pre>{}</pre></details>\n",
                       name, html_escape(text));
  };
  if (!data.report.is_null()) add("report.json", data.report.dump(2));
  if (!data.certificate.is_null())
    add(page.certificate->kind == "certificate" ? "certificate.json" : "validation report",
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
  Json scene{{"units", data.units},
             {"heat_range", heat_range},
             {"colours", page_colours_json()},
             {"view", to_json(guess_view_frame(data.avatar.vertices))},
             {"avatar",
              {{"positions", encode_positions(data.avatar.vertices)},
               {"faces", encode_indices(data.avatar.faces)}}},
             {"garments", garments}};
  if (data.animation) scene["animation"] = page_animation_scene(data);
  return scene;
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
  if (data.animation) body += frame_slider_html(*data.animation);
  body += legend_html(data, heat_range);
  if (has_ease(data)) body += ease_legend_html();
  body += std::string("<p class=\"hint\">Drag to orbit, scroll to zoom, right-drag to pan") +
          (has_shape_toggle(data) ? "; T toggles the garment's shape" : "") + ".</p>\n";
  body += "</section>\n<aside class=\"numbers\">\n";
  const PageReport page = read_page_report(data.report, data.certificate);
  body += verdict_html(page);
  std::vector<Section> sections = page.run
                                      ? retarget_sections(*page.run, page.certificate, data.units)
                                      : validation_sections(page.certificate, data.units);
  sections.push_back(warnings_section(page));
  for (const Section& s : sections) body += section_html(s);
  body += documents_html(data, page);
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
