// Tests of run/paper/paper_run.cpp and run/paper/paper_document.cpp: the
// whole `gpm paper` run on a reduced budget (Table 1's search shortened):
// every table and figure of the paper is there with the printed and this
// run's columns, every difference has its sentence, paper.json parses and
// agrees with paper.md, and the reproduced numbers hold against independent
// facts (the paper's printed initial estimates, the actual values).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "calib/paper_values.hpp"
#include "models/errors.hpp"
#include "run/paper/paper_document.hpp"
#include "run/paper/paper_run.hpp"

namespace gpm::paper {
namespace {

class PaperRunTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    PaperSettings s;
    s.budget = 20000;
    s.table8_evaluations = 20000;
    s.zero_circle_points = 8;
    s.zero_d_min_mm = 1.0;
    run_ = new PaperRun(run_paper(s));
  }
  static void TearDownTestSuite() {
    delete run_;
    run_ = nullptr;
  }
  static const Table& table(const std::string& id) {
    for (const Table& t : run_->tables)
      if (t.id == id) return t;
    throw std::runtime_error("no table " + id);
  }
  static const Row& row(const Table& t, const std::string& quantity) {
    for (const Row& r : t.rows)
      if (r.quantity == quantity) return r;
    throw std::runtime_error("no row " + quantity + " in " + t.id);
  }
  static PaperRun* run_;
};
PaperRun* PaperRunTest::run_ = nullptr;

TEST_F(PaperRunTest, EveryTableAndFigureIsThereWithBothColumns) {
  const std::vector<std::string> ids{"table1", "table2", "table3", "table4", "table5", "table6",
                                     "figure3", "figure4", "figure5", "table7", "table8"};
  ASSERT_EQ(run_->tables.size(), ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    const Table& t = run_->tables[i];
    EXPECT_EQ(t.id, ids[i]);
    EXPECT_FALSE(t.setup.empty()) << t.id;
    EXPECT_FALSE(t.rows.empty()) << t.id;
    int printed = 0;
    for (const Row& r : t.rows) {
      EXPECT_FALSE(r.paper_text.empty()) << t.id << " " << r.quantity;
      EXPECT_FALSE(r.ours_text.empty()) << t.id << " " << r.quantity;
      if (r.paper && r.ours) ++printed;
    }
    EXPECT_GT(printed, 0) << t.id << " compares no printed number";
    if (t.id.rfind("figure", 0) == 0) {
      EXPECT_NE(t.figure_svg.find("<svg"), std::string::npos) << t.id;
    }
  }
}

TEST_F(PaperRunTest, EveryDifferenceHasItsSentence) {
  for (const Table& t : run_->tables) {
    for (const Row& r : t.rows) {
      if (r.reason == Reason::kAgrees) {
        // Agreeing rows really agree with the printed digits.
        if (r.paper && r.ours) {
          EXPECT_LE(std::fabs(*r.ours - *r.paper), printed_half_unit(r.paper_text) * (1 + 1e-9))
              << t.id << " " << r.quantity;
        }
        continue;
      }
      EXPECT_GT(r.why.size(), 20u) << t.id << " " << r.quantity;
      EXPECT_EQ(r.why.back(), '.') << t.id << " " << r.quantity << ": not a sentence: " << r.why;
    }
  }
}

TEST_F(PaperRunTest, ErrataAreCitedWhereThePaperIsWrong) {
  // Section 3's l_a^3 (printed 243.5, must be 244.5).
  const Row& la3 = row(table("table3"), "actual la3");
  EXPECT_EQ(la3.reason, Reason::kPaperMistake);
  EXPECT_NE(la3.why.find("PAPER_NOTES"), std::string::npos);
  // Table 7's kmrmse does not belong to its own printed solution.
  const Row& k = row(table("table7"), "kmrmse of the paper's printed solution on this run's samples");
  EXPECT_EQ(k.reason, Reason::kPaperMistake);
  ASSERT_TRUE(k.ours);
  EXPECT_GT(*k.ours, 0.1);  // errata: about 0.19 mm on the paper's samples, not 0.037
}

TEST_F(PaperRunTest, Table2RunsOnTheNominalMechanismWhoseReadingsGiveThePrintedInitialEstimates) {
  // Independent fact: the paper's printed initial offsets of Table 2 come
  // from the reading at (210, 245); on the nominal mechanism (offsets 1.0)
  // the run reproduces them to every printed digit, on section 3's actual
  // values it does not (up to 9e-5 rad off).
  const auto p2 = calib::printed_table2();
  double worst_actual = 0;
  for (int i = 0; i < 3; ++i) {
    const std::string q = "initial estimate dth" + std::to_string(i + 1);
    const Row& r = row(table("table2"), q);
    EXPECT_EQ(r.reason, Reason::kAgrees) << q;
    ASSERT_TRUE(r.ours);
    EXPECT_NEAR(*r.ours, p2.initial[static_cast<size_t>(i)], 5e-6) << q;
    const Row& a = row(table("table2"), q + ", section 3's actual values");
    ASSERT_TRUE(a.ours);
    worst_actual = std::max(worst_actual, std::fabs(*a.ours - p2.initial[static_cast<size_t>(i)]));
  }
  EXPECT_GT(worst_actual, 5e-5);
  EXPECT_LT(worst_actual, 2e-4);
  EXPECT_EQ(row(table("table2"), "initial estimate dth3, section 3's actual values").reason, Reason::kSetup);
  // No open question is left in Table 2.
  for (const Row& r : table("table2").rows) EXPECT_NE(r.reason, Reason::kOpen) << r.quantity;
}

TEST_F(PaperRunTest, Table4KmrmseIsPlacedByComputedValuesAndTable8InconsistencyIsStated) {
  const Table& t4 = table("table4");
  const Row& initial = row(t4, "kmrmse of the printed initial estimate");
  const Row& family = row(t4, "kmrmse of the family point at the printed 12-parameter offsets");
  ASSERT_TRUE(initial.ours && family.ours);
  EXPECT_GT(std::fabs(*initial.ours - 3.3521), 5 * std::fabs(*family.ours - 3.3521));
  EXPECT_EQ(initial.reason, Reason::kPaperMistake);
  const Row& j3 = row(table("table8"), "J3 at the nominal values, the paper's calibrated values as the robot (median)");
  ASSERT_TRUE(j3.ours);
  EXPECT_GT(*j3.ours, 10 * 2.1517e5);  // the printed value is far below what eq. 43 gives
  EXPECT_EQ(j3.reason, Reason::kPaperMistake);
  EXPECT_NE(j3.why.find("do not fit eq. 43"), std::string::npos);
}

TEST_F(PaperRunTest, Tables3And4InitialDth3ComesFromTheMisprintedLa3) {
  // Independent fact: the printed initial estimates of Tables 3 and 4 (all
  // three joints) are reproduced to their digits only when the reading at
  // (210, 245) is taken from a mechanism with l_a^3 = 243.5.
  for (const std::string id : {"table3", "table4"}) {
    const Table& t = table(id);
    EXPECT_EQ(row(t, "initial estimate dth1").reason, Reason::kAgrees) << id;
    EXPECT_EQ(row(t, "initial estimate dth2").reason, Reason::kAgrees) << id;
    EXPECT_EQ(row(t, "initial estimate dth3").reason, Reason::kPaperMistake) << id;
    EXPECT_EQ(row(t, "initial estimate dth3, reading with l_a^3 = 243.5").reason, Reason::kAgrees) << id;
  }
}

TEST_F(PaperRunTest, ElevenParametersRecoverTheActualValuesTwelveDoNot) {
  const Geometry actual = calib::section3_actual();
  const Table& t = table("table4");
  for (const std::string name : {"la1", "lb3", "xa3", "ya3"}) {
    const Row& r = row(t, name + ", 11 free");
    ASSERT_TRUE(r.ours);
    EXPECT_NEAR(*r.ours, actual[*param_index(name)], 1e-6) << name;
  }
  double worst12 = 0;
  for (const std::string name : {"la1", "la2", "la3", "lb1", "lb2", "lb3", "xa3", "ya3", "xa2"}) {
    worst12 = std::max(worst12, std::fabs(*row(t, name + ", 12 free").ours - actual[*param_index(name)]));
  }
  EXPECT_GT(worst12, 1e-3);  // a point of the similarity family, not the actual values
}

TEST_F(PaperRunTest, JsonParsesAndAgreesWithTheMarkdown) {
  const std::string md = paper_document(*run_).markdown();
  const auto j = nlohmann::json::parse(paper_json(*run_));
  ASSERT_EQ(j["tables"].size(), run_->tables.size());
  EXPECT_EQ(j["budget"].get<long>(), 20000);
  for (const auto& jt : j["tables"]) {
    const std::string title = jt["title"].get<std::string>();
    EXPECT_NE(md.find("## " + title), std::string::npos) << title;
    const Table& t = table(jt["id"].get<std::string>());
    ASSERT_EQ(jt["rows"].size(), t.rows.size());
    for (size_t i = 0; i < t.rows.size(); ++i) {
      const auto& jr = jt["rows"][i];
      const std::string ours = jr["ours_text"].get<std::string>();
      if (!jr["ours"].is_null()) {
        EXPECT_NEAR(std::stod(ours), jr["ours"].get<double>(), 1e-5 * std::fabs(jr["ours"].get<double>()) + 1e-300);
      }
      // The row's line in paper.md carries the same quantity, printed value, value and reason.
      const std::string line = "| " + jr["quantity"].get<std::string>() + " | " + jr["unit"].get<std::string>() +
                               " | " + jr["paper_text"].get<std::string>() + " | " + ours + " |";
      const size_t at = md.find(line);
      ASSERT_NE(at, std::string::npos) << line;
      const std::string rest = md.substr(at, md.find('\n', at) - at);
      const std::string cell = reason_cell(t, t.rows[i]);
      EXPECT_NE(rest.find(cell + " |"), std::string::npos) << rest;
      // A numbered reason's sentence is printed under its table.
      if (jr["reason"] != "agrees") {
        const std::string num = cell.substr(0, cell.find(']') + 1);
        EXPECT_NE(md.find("- " + num + " " + jr["why"].get<std::string>()), std::string::npos) << num;
      }
    }
  }
}

TEST_F(PaperRunTest, WritesAllFilesOrNone) {
  const auto dir = std::filesystem::temp_directory_path() / ("gpm_test_paper_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  write_paper(*run_, dir.string());
  for (const char* f : {"paper.md", "paper.html", "paper.json", "figure3.svg", "figure4.svg", "figure5.svg"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  std::ifstream in(dir / "paper.json");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NO_THROW(nlohmann::json::parse(ss.str()));
  std::filesystem::remove_all(dir);
}

TEST(PaperRunInput, BudgetBelowOneIsRefusedBeforeAnythingRuns) {
  PaperSettings s;
  s.budget = 0;
  EXPECT_THROW(run_paper(s), InputError);
}

}  // namespace
}  // namespace gpm::paper
