#include "run/compare_report_data.hpp"

namespace gpm::scenario {

using calib::cost_name;
using calib::method_name;

report::CompareReport compare_report_data(const calib::global::Comparison& c) {
  const auto& st = c.settings;
  report::CompareReport r;
  r.samples = c.samples.size();
  r.data_seed = st.data_seed;
  r.free = st.free;
  r.budget = st.budget;
  r.seeds = st.seeds;
  r.seconds = c.seconds;
  for (calib::Method m : st.methods) r.methods.emplace_back(method_name(m));
  for (calib::Cost cost : st.costs) {
    r.costs.emplace_back(cost_name(cost));
    std::vector<double> row;
    for (calib::Method m : st.methods) row.push_back(calib::global::paper_table6(m, cost));
    r.paper_j.push_back(row);
  }
  r.diagnosis = c.at_actual.diagnosis;
  r.rank = c.at_actual.rank;
  r.free_count = c.at_actual.free_count;
  r.actual = c.actual;
  for (const auto& run : c.runs)
    r.runs.push_back({std::string(method_name(run.method)), std::string(cost_name(run.cost)), run.seed,
                      run.result.final_cost, run.result.seconds, run.result.evaluations, run.result.rank,
                      run.max_error_mm, run.max_error_rad, run.kmrmse_mm, run.result.geometry, run.result.history});
  return r;
}

}  // namespace gpm::scenario
