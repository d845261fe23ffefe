#include "report_page/page_report.hpp"

#include <stdexcept>

namespace gr {

namespace {

/// The stages the page lists, in pipeline order ("proxy" is part of the fit's time).
constexpr const char* kListedStages[] = {"read", "normalize", "shrink",  "inflate",
                                         "fit",  "write",     "certify", "total"};

/// An object of a document with its address, which every error names.
template <typename J>
class Part {
 public:
  Part(const J& object, std::string document, std::string pointer)
      : object_(object), document_(std::move(document)), pointer_(std::move(pointer)) {
    if (!object_.is_object()) fail("", "is not an object");
  }

  std::string text(const char* key) const {
    const J& v = at(key);
    if (!v.is_string()) fail(key, "is not a string");
    return v.template get<std::string>();
  }

  int count(const char* key) const { return count_of(at(key), key); }

  /// A number, empty where the document wrote null (a NaN or an infinity).
  std::optional<double> number(const char* key) const {
    const J& v = at(key);
    if (v.is_null()) return std::nullopt;
    if (!v.is_number()) fail(key, "is not a number");
    return v.template get<double>();
  }

  bool flag(const char* key) const {
    const J& v = at(key);
    if (!v.is_boolean()) fail(key, "is not true or false");
    return v.template get<bool>();
  }

  std::vector<std::string> texts(const char* key) const {
    std::vector<std::string> out;
    for (const J& v : array(key)) {
      if (!v.is_string()) fail(key, "holds a value that is not a string");
      out.push_back(v.template get<std::string>());
    }
    return out;
  }

  std::vector<int> counts(const char* key) const {
    std::vector<int> out;
    for (const J& v : array(key)) out.push_back(count_of(v, key));
    return out;
  }

  std::vector<double> numbers(const char* key) const {
    std::vector<double> out;
    for (const J& v : array(key)) {
      if (!v.is_number()) fail(key, "holds a value that is not a number");
      out.push_back(v.template get<double>());
    }
    return out;
  }

  Part part(const char* key) const { return {at(key), document_, address(key)}; }

  /// A part the document must name but may write as null.
  std::optional<Part> nullable_part(const char* key) const {
    if (at(key).is_null()) return std::nullopt;
    return part(key);
  }

  std::vector<Part> parts(const char* key) const {
    std::vector<Part> out;
    const std::string list = address(key);
    for (const J& v : array(key))
      out.emplace_back(v, document_, list + "/" + std::to_string(out.size()));
    return out;
  }

  /// A text the document may leave out: empty then.
  std::string optional_text(const char* key) const { return has(key) ? text(key) : ""; }

  std::optional<bool> optional_flag(const char* key) const {
    if (!has(key)) return std::nullopt;
    return flag(key);
  }

  bool has(const char* key) const { return object_.contains(key); }
  /// A key the document may leave out, or write as null.
  bool has_value(const char* key) const { return has(key) && !object_.at(key).is_null(); }

 private:
  const J& at(const char* key) const {
    if (!object_.contains(key)) fail(key, "is missing");
    return object_.at(key);
  }

  const J& array(const char* key) const {
    const J& v = at(key);
    if (!v.is_array()) fail(key, "is not a list");
    return v;
  }

  int count_of(const J& v, const char* key) const {
    if (!v.is_number_integer()) fail(key, "is not a whole number");
    return v.template get<int>();
  }

  std::string address(const char* key) const { return pointer_ + "/" + key; }

  [[noreturn]] void fail(const char* key, const std::string& what) const {
    const std::string where = *key ? address(key) : pointer_.empty() ? "the document" : pointer_;
    throw std::invalid_argument("report page: " + document_ + " " + where + " " + what);
  }

  const J& object_;
  std::string document_;
  std::string pointer_;
};

/// Calls `read` on the part at `key` when the document has it.
template <typename J, typename Read>
auto optional_part(const Part<J>& parent, const char* key, Read read)
    -> std::optional<decltype(read(parent.part(key)))> {
  if (!parent.has(key)) return std::nullopt;
  return read(parent.part(key));
}

RunPageReport read_run(const Part<nlohmann::json>& r) {
  using P = Part<nlohmann::json>;
  RunPageReport run;
  run.quality = r.optional_text("quality");
  run.certified = r.optional_flag("certified");
  run.fit_error = optional_part(r, "fit_error", [](const P& p) {
    return ReportFitError{p.number("mean"), p.number("p95")};
  });
  run.fit = optional_part(r, "fit", [](const P& p) {
    return ReportFitSolve{p.text("status"), p.count("newton_iterations")};
  });
  run.inflate = optional_part(r, "inflate", [](const P& p) {
    return ReportInflate{p.text("status"), p.count("al_rounds"), p.count("resets"),
                         p.count("newton_iterations")};
  });
  run.modelled = optional_part(r, "modelled", [](const P& p) {
    return ReportModelled{
        p.texts("terms"),     p.text("self_contact_where"),  p.count("garment_faces"),
        p.count("fit_faces"), p.count("avatar_faces_total"), p.count("avatar_faces_modelled")};
  });
  run.ease = optional_part(r, "ease", [](const P& p) {
    return ReportEase{p.text("fit"), p.text("source"), p.count("measured_vertices"),
                      p.number("median_ratio"), p.number("within_25_percent")};
  });
  run.untangle = optional_part(r, "untangle", [](const P& p) {
    return ReportUntangle{p.count("pairs"), p.count("resolved"), p.count("remaining"),
                          p.number("max_displacement")};
  });
  run.inherited_crossings = optional_part(r, "inherited_crossings", [](const P& p) {
    return ReportInheritedCrossings{p.count("pairs"), p.count("still_crossing"),
                                    p.count("attached_pieces")};
  });
  run.split_non_manifold_edges = optional_part(r, "split_non_manifold_edges", [](const P& p) {
    return ReportSplitEdges{p.count("edges"), p.count("vertex_copies")};
  });
  run.pierced_faces = optional_part(r, "pierced_faces", [](const P& p) {
    return ReportPiercedFaces{p.counts("left_out_of_contact"), p.counts("opened"),
                              p.texts("bones")};
  });
  if (r.has("min_distance")) run.min_distance = r.part("min_distance").number("avatar_units");
  run.shape = optional_part(r, "shape", [](const P& p) {
    return ReportShape{p.number("scale"),
                       p.number("mean_edge_change"),
                       p.number("p95_edge_change"),
                       p.number("area_change"),
                       p.number("loop_displacement"),
                       p.number("surface_energy_per_area")};
  });
  if (r.has("position")) run.loop_offsets = r.part("position").numbers("loop_offsets");
  run.shrink = optional_part(r, "shrink", [](const P& p) {
    return ReportShrink{p.text("mode"), p.number("depth")};
  });
  if (r.has("seconds")) {
    const P seconds = r.part("seconds");
    for (const char* stage : kListedStages) run.seconds.push_back({stage, seconds.number(stage)});
  }
  if (r.has_value("peak_memory_mb")) run.peak_memory_mb = r.number("peak_memory_mb");
  if (r.has("warnings")) run.warnings = r.texts("warnings");
  return run;
}

CertificatePageReport read_certificate(const Part<nlohmann::ordered_json>& c) {
  using P = Part<nlohmann::ordered_json>;
  CertificatePageReport certificate;
  certificate.kind = c.optional_text("kind");
  certificate.certified = c.optional_flag("certified");
  certificate.counts = optional_part(c, "counts", [](const P& p) {
    return CertificateCounts{p.count("garment_avatar_intersections"),
                             p.count("garment_self_intersections"),
                             p.count("garment_garment_intersections")};
  });
  if (c.has("garments"))
    for (const P& g : c.parts("garments")) {
      CertificateGarment garment{g.text("path"),
                                 g.part("avatar_intersections").count("count"),
                                 g.part("self_intersections").count("count"),
                                 g.part("degenerate_faces").count("count"),
                                 g.part("avatar_clearance").number("distance"),
                                 std::nullopt};
      if (const std::optional<P> near = g.nullable_part("near_vertices"))
        garment.near_vertices =
            CertificateNearVertices{near->number("threshold"), near->count("count")};
      certificate.garments.push_back(std::move(garment));
    }
  if (c.has("issues"))
    for (const P& m : c.part("issues").parts("messages"))
      certificate.messages.push_back({m.text("code"), m.text("severity"), m.text("message")});
  return certificate;
}

}  // namespace

PageReport read_page_report(const nlohmann::json& report,
                            const nlohmann::ordered_json& certificate) {
  PageReport page;
  if (!report.is_null()) page.run = read_run(Part<nlohmann::json>(report, "report.json", ""));
  if (!certificate.is_null())
    page.certificate =
        read_certificate(Part<nlohmann::ordered_json>(certificate, "certificate", ""));
  return page;
}

}  // namespace gr
