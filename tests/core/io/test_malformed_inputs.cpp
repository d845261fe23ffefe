#include <string>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "core/io/obj_document.hpp"
#include "core/io/rig_files.hpp"
#include "test_support.hpp"

namespace {

struct MalformedCase {
  const char* file;
  const char* reader;  ///< "obj", "skeleton", "skin" (2 joints × 3 vertices), "nofit" (10 vertices)
  const char* message;  ///< expected part of the error
  int line;             ///< expected line in the error, 0 when the whole file is at fault
};

void read_with(const std::string& reader, const std::string& path) {
  if (reader == "obj")
    gr::read_obj(path);
  else if (reader == "skeleton")
    gr::read_skeleton(path);
  else if (reader == "skin")
    gr::read_skin_weights(path, 2, 3);
  else
    gr::read_vertex_list(path, 10);
}

}  // namespace

TEST_CASE("malformed files give one error naming file and line", "[io][errors]") {
  const MalformedCase cases[] = {
      {"empty.obj", "obj", "file is empty", 0},
      {"blank.obj", "obj", "file is empty", 0},
      {"binary.obj", "obj", "binary data", 0},
      {"truncated_vertex.obj", "obj", "three coordinates", 5},
      {"malformed_number.obj", "obj", "malformed number '1x'", 4},
      {"nan_coordinate.obj", "obj", "non-finite number 'nan'", 2},
      {"inf_coordinate.obj", "obj", "non-finite number 'inf'", 3},
      {"index_out_of_range.obj", "obj", "vertex index 4 out of range", 4},
      {"index_zero.obj", "obj", "vertex index 0", 4},
      {"negative_index_out_of_range.obj", "obj", "vertex index -4 out of range", 4},
      {"face_two_vertices.obj", "obj", "face with 2 vertices", 4},
      {"texcoord_out_of_range.obj", "obj", "texture coordinate index 2 out of range", 5},
      {"normal_out_of_range.obj", "obj", "normal index 2 out of range", 5},
      {"no_vertices.obj", "obj", "no vertices", 0},
      {"vertex_two_coordinates.obj", "obj", "three coordinates", 1},
      {"face_garbage_index.obj", "obj", "malformed integer 'x'", 4},
      {"skeleton_bone_out_of_range.obj", "skeleton", "joint index 3 out of range", 3},
      {"skeleton_no_bones.obj", "skeleton", "no bones", 0},
      {"skeleton_self_bone.obj", "skeleton", "joins a joint to itself", 3},
      {"skin_ragged.txt", "skin", "2 columns", 2},
      {"skin_negative.txt", "skin", "negative skin weight", 1},
      {"nofit_negative.txt", "nofit", "negative vertex id -3", 2},
      {"nofit_out_of_range.txt", "nofit", "vertex id 99 out of range", 1},
      {"nofit_garbage.txt", "nofit", "malformed integer 'two'", 1},
      {"does_not_exist.obj", "obj", "cannot open file", 0},
  };
  for (const auto& c : cases) {
    const std::string path = gr::test::project_file(std::string("tests/data/malformed/") + c.file);
    CAPTURE(c.file);
    try {
      read_with(c.reader, path);
      FAIL("no error for " << c.file);
    } catch (const gr::InputError& e) {
      const std::string message = e.what();
      CAPTURE(message);
      CHECK(e.file() == path);
      CHECK(e.line() == static_cast<std::size_t>(c.line));
      CHECK(message.find(c.message) != std::string::npos);
      CHECK(message.rfind(path, 0) == 0);
      CHECK(message.find('\n') == std::string::npos);
    }
  }
}

TEST_CASE("skin weights with the wrong number of rows are rejected", "[io][errors]") {
  const std::string path = gr::test::project_file("tests/data/malformed/skin_too_few_rows.txt");
  CHECK_THROWS_WITH(gr::read_skin_weights(path, 3, 3),
                    Catch::Contains("2 rows, expected one per joint (3)"));
}

TEST_CASE("skeletons with different joints or bones do not match", "[io][errors]") {
  gr::Skeleton a;
  a.joints = gr::MatrixX3d::Zero(3, 3);
  a.bones.resize(2, 2);
  a.bones << 0, 1, 1, 2;
  gr::Skeleton reversed = a;
  reversed.bones << 1, 0, 2, 1;
  CHECK_NOTHROW(gr::check_skeletons_match(a, reversed, "t.obj"));

  gr::Skeleton fewer = a;
  fewer.joints = gr::MatrixX3d::Zero(2, 3);
  CHECK_THROWS_WITH(gr::check_skeletons_match(a, fewer, "t.obj"), Catch::Contains("2 joints"));

  gr::Skeleton other = a;
  other.bones << 0, 1, 0, 2;
  CHECK_THROWS_WITH(gr::check_skeletons_match(a, other, "t.obj"), Catch::Contains("bones differ"));
}
