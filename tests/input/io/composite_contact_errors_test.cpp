// [contact] composite_special_case (docs/scenario.md, theory §6.1.1): a bad value names the file,
// line, column, the valid values and the closest one; the CLI exits with 2.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "fdem/error.hpp"
#include "fdem/scenario.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// line numbers: the [contact] table is on line 13, its composite_special_case on line 15
std::string scenario(const std::string& value) {
    return R"([simulation]
end_time = 0.01
dt = "auto"
[[material]]
name = "rock"
density = 2700.0
youngs_modulus = 5e10
poisson_ratio = 0.25
[[body]]
name = "block"
mesh = "square_41_ascii.msh"
material = "rock"
[contact]
algorithm = "smooth"
composite_special_case = )" +
           value + "\n";
}

TEST(CompositeContactErrors, UnknownOptionNamesTheValidOnes) {
    const std::string w = support::scenario_error(scenario("\"fann\""));
    EXPECT_THAT(w, StartsWith("bad.toml:15:26: error: [contact]: composite_special_case must be "
                              "one of \"fan\", \"split\", got \"fann\"; did you mean \"fan\"?"));
}

TEST(CompositeContactErrors, WrongTypeIsAnError) {
    const std::string w = support::scenario_error(scenario("2"));
    EXPECT_THAT(w, StartsWith("bad.toml:15:26: error: [contact]: composite_special_case must be "));
}

TEST(CompositeContactErrors, ValidOptionsLoad) {
    const Scenario fan =
        load_scenario_from_string(scenario("\"fan\""), "ok.toml", FDEM_TEST_DATA_DIR);
    EXPECT_EQ(fan.model.contact.composite_special_case, CompositeSpecialCase::Fan);
    const Scenario split =
        load_scenario_from_string(scenario("\"split\""), "ok.toml", FDEM_TEST_DATA_DIR);
    EXPECT_EQ(split.model.contact.composite_special_case, CompositeSpecialCase::Split);
}

TEST(CompositeContactErrors, CliExitsWithCode2) {
    const std::string dir = ::testing::TempDir();
    const std::string path = dir + "/composite_bad.toml";
    {
        std::string text = scenario("\"split-ten\"");
        // the CLI reads the mesh relative to the scenario file: give its absolute path
        const std::string mesh = "\"square_41_ascii.msh\"";
        text.replace(text.find(mesh), mesh.size(),
                     "\"" + std::string(FDEM_TEST_DATA_DIR) + "/square_41_ascii.msh\"");
        std::ofstream(path) << text;
    }
    const std::string err = dir + "/composite_bad.err";
    const std::string cmd =
        std::string(FDEM_CLI_PATH) + " check " + path + " > /dev/null 2> " + err;
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2);
    std::ifstream in(err);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_THAT(text, HasSubstr(path + ":15:26: error: [contact]: composite_special_case must be "
                                       "one of \"fan\", \"split\", got \"split-ten\""));
}

}  // namespace
}  // namespace fdem
