// Tests harness/report/verdict_files.cpp: the JUnit and JSON verdicts of `check` count and carry
// what the printed lines do, with hostile text escaped (ctest check.verdict_files validates real
// runs against the schemas).
#include "harness/report/verdict_files.hpp"

#include <catch2/catch.hpp>
#include <sstream>

using namespace dropcheck;
using Catch::Contains;

TEST_CASE("check's verdict files: one case a record, failures and skips counted, text escaped",
          "[check][junit]") {
  std::vector<CheckRecord> records(4);
  records[0].result = {"free_fall", "ode", "own law at h = 1/60", true, "", "max |x - law| 0 m"};
  records[1].result = {"free_fall", "evil", "own law",
                       false,       "",     "x < 1 & \"y\" > 2\x01 'z'\nnext \xff\xfe \xC3\xA9"};
  records[2].result = {"thin_floor", "ode", "landing", true, "tunnels", "ends below"};
  records[3].result.scene = "throw_3d";
  records[3].result.engine = "box2d";
  records[3].skipped = true;
  records[3].skipped_because = "not planar";
  std::ostringstream xml, json;
  write_junit(xml, records);
  write_check_json(json, records);
  CHECK_THAT(
      xml.str(),
      Contains("<testsuites name=\"dropcheck check\" tests=\"4\" failures=\"1\" errors=\"0\" "
               "skipped=\"1\">") &&
          Contains("<testsuite name=\"free_fall\" tests=\"2\" failures=\"1\"") &&
          Contains("x &lt; 1 &amp; &quot;y&quot; &gt; 2\xEF\xBF\xBD &apos;z&apos;&#10;next "
                   "\xEF\xBF\xBD\xEF\xBF\xBD \xC3\xA9") &&
          Contains("<system-out>LIMIT tunnels; ends below</system-out>") &&
          Contains("<skipped message=\"not planar\"/>"));
  CHECK_THAT(json.str(), Contains("\"passed\": 1") && Contains("\"limits\": 1") &&
                             Contains("\"failed\": 1") && Contains("\"skipped\": 1") &&
                             Contains("\"verdict\": \"limit\"") &&
                             Contains("x < 1 & \\\"y\\\" > 2\\u0001 'z'"));
  CHECK(verdict_word(records[3]) == "skipped");
}
