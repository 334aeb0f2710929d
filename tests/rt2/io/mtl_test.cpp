// tests/rt2/io/mtl_test.cpp — rt2::io::read_mtl and from_mtl (rt2/io/mtl.h): one number is a
// grey colour; every number is checked, a bad one named with its file and line; Ns 0 means
// no highlight; only the materials asked for are kept, the first definition of a name wins;
// textures are warned about once per file.
#include "rt2/io/mtl.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rt2/base/error.h"

namespace rt2::io {
namespace {

MtlMaterials wanting(std::initializer_list<const char*> names) {
  MtlMaterials m;
  for (const char* n : names) m.try_emplace(n);
  return m;
}

// The material `name` of `text`, read as file "m.mtl".
MtlMaterial read_one(const std::string& text, const char* name = "m") {
  MtlMaterials m = wanting({name});
  read_mtl("m.mtl", text, m);
  EXPECT_TRUE(m.at(name).has_value()) << name;
  return m.at(name).value_or(MtlMaterial{});
}

void expect_rgb(const vec4& v, float r, float g, float b) {
  EXPECT_FLOAT_EQ(v[0], r);
  EXPECT_FLOAT_EQ(v[1], g);
  EXPECT_FLOAT_EQ(v[2], b);
}

std::string error_of(const std::string& text) {
  MtlMaterials m = wanting({"m"});
  try {
    read_mtl("m.mtl", text, m);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for: " << text;
  return {};
}

TEST(Mtl, OneNumberIsAGreyColour) {
  // tinyobjloader reads `Kd 0.5` as (0.5, 0, 0): dark red.
  const Material m = from_mtl(read_one("newmtl m\nKa 0.1\nKd 0.5\nKs 0.25\nKe 1\nTf 0.5\n"));
  expect_rgb(m.ambient, 0.1f, 0.1f, 0.1f);
  expect_rgb(m.diffuse, 0.5f, 0.5f, 0.5f);
  expect_rgb(m.specular, 0.25f, 0.25f, 0.25f);
  expect_rgb(from_mtl(read_one("newmtl m\nKd 0.2 0.4 0.6\n")).diffuse, 0.2f, 0.4f, 0.6f);
}

TEST(Mtl, EveryNumberIsCheckedAndNamedWithItsLine) {
  const std::string m = "newmtl m\n";
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {m + "Ns nan\n", "m.mtl:2: material 'm': Ns must be a finite number (got 'nan')"},
           {m + "Kd nan\n", "m.mtl:2: material 'm': Kd must be a finite number (got 'nan')"},
           {m + "Kd red green blue\n", "m.mtl:2: material 'm': Kd must be a number (got 'red')"},
           {m + "Ka 0.5 0.5\n", "m.mtl:2: material 'm': Ka needs 1 or 3 numbers (got 2)"},
           {m + "Ks 1 1 1 1\n", "m.mtl:2: material 'm': Ks needs 1 or 3 numbers (got 4)"},
           {m + "Ke\n", "m.mtl:2: material 'm': Ke needs 1 or 3 numbers (got 0)"},
           {m + "Tf 1 inf 1\n", "m.mtl:2: material 'm': Tf must be a finite number (got 'inf')"},
           {m + "Kt 1e39\n", "m.mtl:2: material 'm': Kt must be a finite number (got '1e39')"},
           {m + "Ni 1.5x\n", "m.mtl:2: material 'm': Ni must be a number (got '1.5x')"},
           {m + "d 0.5 0.5\n", "m.mtl:2: material 'm': d needs 1 number (got 2)"},
           {m + "d -halo\n", "m.mtl:2: material 'm': d needs 1 number (got 0)"},
           {m + "Tr -nan\n", "m.mtl:2: material 'm': Tr must be a finite number (got '-nan')"},
           {m + "illum two\n",
            "m.mtl:2: material 'm': illum must be an integer from 0 to 10 (got 'two')"},
           {m + "illum 2.5\n", "illum must be an integer from 0 to 10 (got '2.5')"},
           {m + "illum 11\n", "illum must be an integer from 0 to 10 (got '11')"},
           {m + "Kr shiny\n", "m.mtl:2: material 'm': Kr must be a number (got 'shiny')"},
           {"# before any material\nNs x\n", "m.mtl:2: Ns must be a number (got 'x')"},
           {"newmtl unused\nKd 1 0 0\nNs nan\n", "m.mtl:3: material 'unused': Ns must be a finite"},
       }) {
    SCOPED_TRACE(text);
    const std::string e = error_of(text);
    EXPECT_NE(e.find(message), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

TEST(Mtl, StatementsThatRt2IgnoresAreAccepted) {
  testing::internal::CaptureStderr();
  const MtlMaterial t = read_one(
      "newmtl m\nKd 1 0 0\nd -halo 0.5\nsharpness 60\nPr 0.5\nPm 0\nillum 2\nKm 1 2 3 4\n"
      "Ka spectral ident.rfl 1\nKs xyz 1 1 1\nmap_Kd -s 1 1 1 wood.png\n");
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_FLOAT_EQ(t.d, 0.5f);
  EXPECT_EQ(t.illum, 2);
  EXPECT_EQ(err.find("map_Kd"), std::string::npos) << err;  // read, not ignored
  EXPECT_EQ(t.map_kd.file, "wood.png");
  EXPECT_EQ(t.map_kd.line, 11u);
  EXPECT_NE(err.find("warning: m.mtl:9: spectral and CIE XYZ colours are not supported"),
            std::string::npos)
      << err;
}

TEST(Mtl, ShininessZeroMeansNoHighlight) {
  // 3ds Max writes Ns 0 with Ks > 0 for matte walls: with exponent 0 the highlight would
  // cover the whole lit side.
  const Material matte = from_mtl(read_one("newmtl m\nKs 0.9\nNs 0\n"));
  expect_rgb(matte.specular, 0, 0, 0);
  EXPECT_FLOAT_EQ(matte.shininess, 0.0f);
  const Material negative = from_mtl(read_one("newmtl m\nKs 0.9\nNs -3\n"));
  expect_rgb(negative.specular, 0, 0, 0);
  // A mirror keeps its reflection; a positive exponent its highlight.
  const Material mirror = from_mtl(read_one("newmtl m\nKs 0.9\nNs 0\nillum 3\n"));
  EXPECT_FLOAT_EQ(mirror.reflectivity, 0.9f);
  expect_rgb(from_mtl(read_one("newmtl m\nKs 0.9\nNs 0.5\n")).specular, 0.9f, 0.9f, 0.9f);
}

TEST(Mtl, OnlyTheMaterialsAskedForAreKeptAndTheFirstDefinitionWins) {
  MtlMaterials m = wanting({"b", "missing"});
  read_mtl("m.mtl", "newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\nnewmtl b\nKd 0 0 1\n", m);
  EXPECT_EQ(m.size(), 2u);
  ASSERT_TRUE(m.at("b").has_value());
  EXPECT_FALSE(m.at("missing").has_value());
  expect_rgb(from_mtl(*m.at("b")).diffuse, 0, 1, 0);
  EXPECT_EQ(m.at("b")->file, "m.mtl");
}

TEST(Mtl, NamesAreTheRestOfTheLine) {
  MtlMaterials m = wanting({"Hard Wood", "red"});
  read_mtl("m.mtl", "newmtl   Hard Wood  \nKd 0.5\nnewmtl\tred\nKd 1 0 0\n", m);
  ASSERT_TRUE(m.at("Hard Wood").has_value());
  ASSERT_TRUE(m.at("red").has_value());
  expect_rgb(from_mtl(*m.at("Hard Wood")).diffuse, 0.5f, 0.5f, 0.5f);
}

TEST(Mtl, TexturesAreWarnedAboutOncePerFile) {
  MtlMaterials m = wanting({"a", "b"});
  testing::internal::CaptureStderr();
  read_mtl("m.mtl", "newmtl a\nmap_Kd a.png\nbump a_bump.png\nnewmtl b\nKd 0.2\nmap_Ks b.png\n", m);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(err,
            "warning: m.mtl:3: 'bump' is not supported; it and the other unsupported texture "
            "statements of this file are ignored (rt2 reads map_Kd, map_Ke, map_Pr, map_Pm and "
            "norm)\n");
  // map_Kd without Kd: tinyobjloader's 0.6 grey, not black.
  expect_rgb(from_mtl(*m.at("a")).diffuse, 0.6f, 0.6f, 0.6f);
  expect_rgb(from_mtl(*m.at("b")).diffuse, 0.2f, 0.2f, 0.2f);
  // Textures of materials nobody uses are not worth a warning.
  MtlMaterials none = wanting({"b"});
  testing::internal::CaptureStderr();
  read_mtl("m.mtl", "newmtl a\nmap_Kd a.png\nnewmtl b\nKd 0.2\n", none);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(Mtl, AbsentValuesKeepTinyobjloadersDefaults) {
  const Material m = from_mtl(read_one("newmtl m\n"));
  expect_rgb(m.ambient, 0, 0, 0);
  expect_rgb(m.diffuse, 0, 0, 0);
  expect_rgb(m.specular, 0, 0, 0);
  EXPECT_FLOAT_EQ(m.shininess, 1.0f);
  EXPECT_FLOAT_EQ(m.ior, 1.5f);  // no Ni: rt2's default, not tinyobjloader's 1
  EXPECT_FLOAT_EQ(m.transparency, 0.0f);
  EXPECT_FLOAT_EQ(m.reflectivity, 0.0f);
}

}  // namespace
}  // namespace rt2::io
