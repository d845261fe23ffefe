#include <catch2/catch.hpp>

#include "stage_chain.hpp"

namespace gr {

TEST_CASE("certify stage: the written file certified, with its shape and fit error",
          "[pipeline][stages]") {
  test::StageChain chain("certify");
  const CertifyOutput& out = chain.certify();
  CHECK(out.report.certified);
  CHECK(out.certificate.certified());
  CHECK(out.report.shape.mean_edge_change < 0.1);
  CHECK(out.report.fit_error.samples > 0);
  CHECK(out.inherited_still_crossing == 0);
  CHECK(out.ease.vertices == 0);  // no source ease
  RetargetReport report;
  report.certify = out.report;
  report.normalize = chain.prepare().report;
  report.fit = chain.fit().report;
  CHECK_THAT(certify_summary(out.certificate, report, 1.0),
             Catch::StartsWith("certified: 0 garment-avatar"));
}

}  // namespace gr
