#include "drivers/json/json_writer.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "tests/support/temp_dir.h"

using sonarloop::json::Writer;

TEST_CASE("json: nested objects and arrays, escaping, numbers") {
  Writer w;
  w.begin_object()
      .field("name", "a \"quoted\"\nline\x01")
      .field("n", 3)
      .field("x", 0.1)
      .field("nan", std::nan(""))
      .field("ok", true);
  w.key("list").begin_array().value(1).value(2.5).begin_object().end_object().null().end_array();
  w.end_object();
  CHECK(
      w.str() ==
      R"({"name":"a \"quoted\"\nline\u0001","n":3,"x":0.1,"nan":null,"ok":true,"list":[1,2.5,{},null]})");
}

TEST_CASE("json: misuse is a logic error") {
  Writer w;
  w.begin_object();
  CHECK_THROWS_AS(w.value(1), std::logic_error);
  Writer a;
  a.begin_array();
  CHECK_THROWS_AS(a.key("k"), std::logic_error);
  CHECK_THROWS_AS(a.end_object(), std::logic_error);
}

TEST_CASE("json: pretty output is valid JSON for Python") {
  sonarloop::testing::TempDir dir("json");
  Writer w(true);
  w.begin_object()
      .field("a", 1)
      .key("b")
      .begin_array()
      .value("x")
      .value(2.0)
      .end_array()
      .end_object();
  const std::string path = dir.file("a.json");
  std::ofstream(path) << w.str();
  const std::string py = std::string(SONARLOOP_PYTHON) +
                         " -c \"import json,sys; d=json.load(open(sys.argv[1])); "
                         "sys.exit(0 if d=={'a':1,'b':['x',2.0]} else 1)\" " +
                         path;
  CHECK(sonarloop::testing::run_command(py) == 0);
}
