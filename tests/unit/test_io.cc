/**
 * @file
 * The io subsystem: output files, data files, parameter-file errors and the
 * parameter reference.
 */
#include <rockdda/io/analysis.h>
#include <rockdda/io/data_file.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/progress.h>
#include <rockdda/io/provenance.h>
#include <rockdda/io/text.h>
#include <rockdda/seismic/record.h>

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include "test_files.h"
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

using namespace rockdda::test_files;

namespace
{
  namespace fs = std::filesystem;



  void
  declare_toy(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Block");
    rockdda::io::declare(
      prm, "Dip", "10", dealii::Patterns::Double(0., 90.), "deg", "Dip.");
    prm.leave_subsection();
  }
} // namespace



TEST(Output, AtomicWriteLeavesNoTemporaryFile)
{
  const auto                         dir = scratch("atomic");
  const rockdda::io::OutputDirectory out((dir / "a" / "b").string());
  out.write("x.csv", "1\n");
  out.write("x.csv", "2\n");
  std::ifstream in(dir / "a" / "b" / "x.csv");
  std::string   text;
  in >> text;
  EXPECT_EQ(text, "2");
  unsigned int n = 0;
  for (const auto &e : fs::directory_iterator(dir / "a" / "b"))
    n += e.is_regular_file()
         && e.path().filename() != rockdda::io::OutputDirectory::manifest_name;
  EXPECT_EQ(n, 1u); // no *.tmp.* left behind
}



TEST(Output, NewRunRemovesOnlyTheFilesOfTheEarlierRun)
{
  const auto dir = scratch("earlier-run");
  {
    const rockdda::io::OutputDirectory out(dir.string());
    for (const char *name : {"blocks-00000.vtu", "blocks-00001.vtu", "a.csv"})
      out.write(name, "x\n");
    out.own("checkpoint-mesh*");
    std::ofstream(dir / "checkpoint-mesh-0_fixed.data") << "p4est\n";
    std::ofstream(dir / "blocks-00001.vtu.tmp.123") << "killed\n";
  }
  std::ofstream(dir / "user-notes.vtu") << "not rockdda's\n";
  const rockdda::io::OutputDirectory out(dir.string());
  EXPECT_EQ(out.remove_earlier_run(), 5u);
  std::vector<std::string> left;
  for (const auto &e : fs::directory_iterator(dir))
    left.push_back(e.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"user-notes.vtu"});
  // The new run's names go into a new manifest.
  out.write("blocks-00000.vtu", "y\n");
  EXPECT_TRUE(fs::exists(dir / rockdda::io::OutputDirectory::manifest_name));
  EXPECT_EQ(out.remove_earlier_run(), 1u);
}



TEST(Progress, LineShowsStepOfPlannedStepsAndEta)
{
  const rockdda::io::ProgressBar bar("dda", 0., 3., 3000);
  EXPECT_EQ(bar.text(1200, 1.2, 8.),
            "dda  step 1200/3000  t = 1.2 s of 3 s   40.0 %  ETA 12 s   ");
  const rockdda::io::ProgressBar adaptive("heat", 10.);
  EXPECT_EQ(adaptive.text(7, 0., 1.),
            "heat  step 7  t = 0 s of 10 s    0.0 %  ETA -   ");
  EXPECT_EQ(rockdda::io::planned_steps(0., 1., 0.001), 1000.);
  EXPECT_EQ(rockdda::io::planned_steps(0., 1.00005, 0.001), 1001.);
  EXPECT_EQ(rockdda::io::planned_steps(0., 12 * 31557600., 1.), 378691200.);
}



TEST(Output, TableHeaderCarriesUnits)
{
  rockdda::io::Table t;
  t.add_column("time", "s");
  t.add_column("velocity", "m/s");
  t.add_column("state", "-");
  t.add_row({0.5, 1.25, 1});
  EXPECT_EQ(t.csv(), "time_s,velocity_m_s,state\n0.5,1.25,1\n");
  EXPECT_THROW(t.add_row({1.}), std::logic_error);
}



TEST(Output, CsvWriterQuotesFieldsAsRfc4180)
{
  using rockdda::io::CsvWriter;
  EXPECT_EQ(CsvWriter::quote("plain"), "plain");
  EXPECT_EQ(CsvWriter::quote("a, b"), "\"a, b\"");
  EXPECT_EQ(CsvWriter::quote("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(CsvWriter::quote("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(CsvWriter::quote(" padded"), "\" padded\"");
  CsvWriter w;
  w.field("x").number(0.1).field("a,\"b\"").end_record();
  EXPECT_EQ(w.text(), "x,0.1,\"a,\"\"b\"\"\"\n");
  // The reader is the inverse of the writer.
  const std::string line = w.text().substr(0, w.text().size() - 1);
  EXPECT_EQ(rockdda::io::split_csv_record(line),
            (std::vector<std::string>{"x", "0.1", "a,\"b\""}));
  EXPECT_THROW(rockdda::io::split_csv_record("\"open"), std::invalid_argument);
}



// A parameter's list text: trimmed fields; a trailing separator is a last,
// empty field (so that a count check sees it); no text, no field.
TEST(Text, SplitFields)
{
  using rockdda::io::split_fields;
  using V = std::vector<std::string>;
  EXPECT_EQ(split_fields(" 0, 0 ; 4,0;\t4, 2 ", ';'),
            (V{"0, 0", "4,0", "4, 2"}));
  EXPECT_EQ(split_fields("a, b,", ','), (V{"a", "b", ""}));
  EXPECT_EQ(split_fields("", ','), V{});
  EXPECT_EQ(split_fields(" single ", '|'), V{"single"});
  EXPECT_EQ(rockdda::io::trim(" \t x y \r"), "x y");
  EXPECT_EQ(rockdda::io::trim("   "), "");
}



TEST(Output, SummaryWithCommasInTextIsValidCsv)
{
  // Issue 11: the heat summary's 'method' holds commas and semicolons; every
  // record of summary.csv must still have exactly three fields.
  rockdda::io::Summary s;
  s.add_text("method",
             "Crank-Nicolson (theta = 1/2), dt = 86459.2 s; FE_Q(2); \"x\"");
  s.add("wall_time", 1.5, "s");
  std::istringstream in(s.csv());
  std::string        line;
  std::getline(in, line);
  EXPECT_EQ(line, "quantity,value,unit");
  std::getline(in, line);
  const auto f = rockdda::io::split_csv_record(line);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0], "method");
  EXPECT_EQ(f[1],
            "Crank-Nicolson (theta = 1/2), dt = 86459.2 s; FE_Q(2); \"x\"");
  EXPECT_EQ(f[2], "text");
  std::getline(in, line);
  EXPECT_EQ(line, "wall_time,1.5,s");
}



TEST(Provenance, Sha256MatchesFips180Vectors)
{
  using rockdda::io::sha256;
  // FIPS 180-4 examples and lengths around the padding boundaries (55, 56,
  // 64, 119 bytes), and one million 'a'.
  EXPECT_EQ(sha256(""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256(std::string(55, 'a')),
            "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
  EXPECT_EQ(sha256(std::string(64, 'a')),
            "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
  EXPECT_EQ(sha256(std::string(119, 'a')),
            "31eba51c313a5c08226adf18d4a359cfdfd8d2e816b13f4af952f7ea6584dcfb");
  EXPECT_EQ(sha256(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}



TEST(Provenance, BuildAndRunAreRecorded)
{
  const auto b = rockdda::io::BuildInfo::current();
  EXPECT_TRUE(
    std::regex_match(b.version, std::regex("[0-9]+\\.[0-9]+\\.[0-9]+")))
    << b.version;
  EXPECT_FALSE(b.git_commit.empty());
  EXPECT_FALSE(b.build_type.empty());
  const char *argv[] = {"rockdda", "--quiet", "my file.prm"};
  const auto  p      = rockdda::io::RunProvenance::current(3, argv);
  EXPECT_EQ(p.command_line, "rockdda --quiet 'my file.prm'");
  EXPECT_TRUE(std::regex_match(
    p.date,
    std::regex("[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z")))
    << p.date;
  EXPECT_FALSE(p.host.empty());
}



TEST(DataFile, MalformedNumberNamesTheLine)
{
  const auto dir = scratch("data");
  write_file(dir / "r.txt", "# header\n0.1\n0.2\n\n0.x3\n");
  const std::string msg = error_of(
    [&]() { rockdda::io::read_columns((dir / "r.txt").string(), 1, 1); });
  EXPECT_NE(msg.find("r.txt:5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("0.x3"), std::string::npos) << msg;

  write_file(dir / "ragged.txt", "1 2\n3\n");
  EXPECT_NE(error_of([&]() {
              rockdda::io::read_columns((dir / "ragged.txt").string(), 1, 2);
            }).find("ragged.txt:2"),
            std::string::npos);
  EXPECT_NE(error_of([&]() {
              rockdda::io::read_columns("/no/such", 1, 1);
            }).find("/no/such"),
            std::string::npos);
}



TEST(Record, ReadsBothLayoutsAndInterpolates)
{
  const auto dir = scratch("record");
  write_file(dir / "one.txt", "0\n1\n-1\n");
  write_file(dir / "two.txt", "0.0 0\n0.5 1\n1.0 -1\n");
  const auto one
    = rockdda::seismic::read_record((dir / "one.txt").string(), 0.5);
  const auto two
    = rockdda::seismic::read_record((dir / "two.txt").string(), 99.);
  EXPECT_DOUBLE_EQ(one.dt, 0.5);
  EXPECT_DOUBLE_EQ(two.dt, 0.5);
  EXPECT_DOUBLE_EQ(one.at(0.25), 0.5);
  EXPECT_DOUBLE_EQ(one.at(0.75), 0.);
  EXPECT_DOUBLE_EQ(one.at(1.0), -1.);
  EXPECT_DOUBLE_EQ(one.at(5.0), 0.); // at rest after the record
  EXPECT_DOUBLE_EQ(one.peak(), 1.);
  EXPECT_NE(error_of([&]() {
              rockdda::seismic::read_record((dir / "one.txt").string(), 0.);
            }).find("dt > 0"),
            std::string::npos);
}



TEST(Parameters, UnknownKeyNamesFileLineAndSection)
{
  const auto dir = scratch("prm");
  write_file(dir / "a.prm",
             "subsection Block\n  set Dip = 10\n  set Dpi = 3\nend\n");
  dealii::ParameterHandler prm;
  declare_toy(prm);
  const std::string msg = error_of([&]() {
    rockdda::io::parse_parameter_file(prm, (dir / "a.prm").string());
  });
  EXPECT_NE(msg.find("a.prm:3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("Dpi"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'Block'"), std::string::npos) << msg;
}



TEST(Parameters, OutOfRangeValueNamesKeyAndRange)
{
  const auto dir = scratch("range");
  write_file(dir / "b.prm", "subsection Block\n  set Dip = 95\nend\n");
  dealii::ParameterHandler prm;
  declare_toy(prm);
  const std::string msg = error_of([&]() {
    rockdda::io::parse_parameter_file(prm, (dir / "b.prm").string());
  });
  EXPECT_NE(msg.find("b.prm:2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'Dip'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("90"), std::string::npos) << msg; // the valid range
}



TEST(Parameters, UnknownSectionAndMissingFile)
{
  const auto dir = scratch("section");
  write_file(dir / "c.prm", "subsection Blok\n  set Dip = 5\nend\n");
  dealii::ParameterHandler prm;
  declare_toy(prm);
  const std::string msg = error_of([&]() {
    rockdda::io::parse_parameter_file(prm, (dir / "c.prm").string());
  });
  EXPECT_NE(msg.find("c.prm:1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("Blok"), std::string::npos) << msg;
  EXPECT_NE(error_of([&]() {
              rockdda::io::parse_parameter_file(prm, "/no/such.prm");
            }).find("/no/such.prm"),
            std::string::npos);
}



TEST(Parameters, ResolvePathExpandsVariablesRelativeToFile)
{
  ::setenv("ROCKDDA_TEST_DIR", "/data/x", 1);
  EXPECT_EQ(rockdda::io::resolve_path("$ROCKDDA_TEST_DIR/r.txt",
                                      "/a/b.prm",
                                      "k"),
            "/data/x/r.txt");
  EXPECT_EQ(rockdda::io::resolve_path("${ROCKDDA_TEST_DIR}/r.txt",
                                      "/a/b.prm",
                                      "k"),
            "/data/x/r.txt");
  EXPECT_EQ(rockdda::io::resolve_path("../r.txt", "/a/b/c.prm", "k"),
            "/a/r.txt");
  EXPECT_NE(error_of([]() {
              rockdda::io::resolve_path("$ROCKDDA_UNSET_VARIABLE/x",
                                        "p.prm",
                                        "Key");
            }).find("ROCKDDA_UNSET_VARIABLE"),
            std::string::npos);
}



TEST(Parameters, EveryKeyDocumentsItsUnit)
{
  // The reference rows are "| `key` | `default` | valid | unit | help |":
  // every key of every analysis must carry a unit ([-] if dimensionless)
  // and a help text.
  dealii::ParameterHandler prm;
  const auto               analyses = rockdda::io::all_analyses();
  rockdda::io::declare_all_parameters(prm, analyses);
  std::ostringstream out;
  rockdda::io::print_parameter_reference(prm, out);
  std::istringstream lines(out.str());
  std::string        line;
  unsigned int       n_keys = 0;
  const std::regex   row(
    "^\\| `([^`]+)` \\| `[^`]*` \\| (.+) \\| (.+) \\| (.+) \\|$");
  while (std::getline(lines, line))
    if (line.rfind("| `", 0) == 0)
      {
        std::smatch m;
        ASSERT_TRUE(std::regex_match(line, m, row)) << line;
        EXPECT_FALSE(m[3].str().empty()) << line;
        EXPECT_GT(m[4].str().size(), 5u) << "help text missing: " << line;
        ++n_keys;
      }
  EXPECT_GT(n_keys, 20u);
}
