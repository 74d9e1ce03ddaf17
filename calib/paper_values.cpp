#include "calib/paper_values.hpp"

#include <initializer_list>
#include <utility>

namespace gpm::calib {

namespace {

// The nominal GPM2002 with the listed parameters (index, value) changed.
Geometry nominal_with(std::initializer_list<std::pair<int, double>> values) {
  Geometry g = Geometry::gpm2002_nominal();
  for (const auto& [i, v] : values) g[i] = v;
  return g;
}

}  // namespace

Geometry section3_actual() {
  return nominal_with({{kXa2, 433.04}, {kXa3, 433.05}, {kYa3, 499.96},
                       {kLa1, 244.1}, {kLa2, 244.2}, {kLa3, 244.5},
                       {kLb1, 243.8}, {kLb2, 244.2}, {kLb3, 244.2},
                       {kDth1, 1.0}, {kDth2, 1.0}, {kDth3, 1.0}});
}

Geometry table5_actual() {
  return nominal_with({{kYa2, 0.3}, {kXa3, 433.5}, {kYa3, 499.4},
                       {kLa1, 244.1}, {kLa2, 244.2}, {kLa3, 243.5},
                       {kLb1, 243.8}, {kLb2, 244.2}, {kLb3, 244.6},
                       {kDth1, 0.01}, {kDth2, -0.01}, {kDth3, 0.01}});
}

FreeMask paper_free_mask() {
  FreeMask m;
  m.set();
  m.reset(kXa1);
  m.reset(kYa1);
  m.reset(kXa2);
  return m;
}

Problem table5_problem(const Samples& s, const FreeMask& free) {
  Problem p;
  p.theta_m = s.theta_m;
  p.free = free;
  p.start = Geometry::gpm2002_nominal();
  const Geometry actual = table5_actual();
  for (int i = 0; i < kNumParams; ++i)
    if (!free[static_cast<size_t>(i)]) p.start[i] = actual[i];
  return p;
}

namespace {

// Parameters not printed stay NaN.
PrintedParams none() {
  PrintedParams p;
  p.fill(kNotPrinted);
  return p;
}

// Offsets, active and passive links in the order of Tables 3 and 4.
void set_links(PrintedParams& p, std::array<double, 9> v) {
  const int idx[9] = {kDth1, kDth2, kDth3, kLa1, kLa2, kLa3, kLb1, kLb2, kLb3};
  for (int k = 0; k < 9; ++k) p[static_cast<size_t>(idx[k])] = v[static_cast<size_t>(k)];
}

// The 12 parameters in the order of Tables 7 and 8.
PrintedParams section4(std::array<double, 12> v) {
  PrintedParams p = none();
  const int idx[12] = {kYa2, kXa3, kYa3, kLa1, kLa2, kLa3, kLb1, kLb2, kLb3, kDth1, kDth2, kDth3};
  for (int k = 0; k < 12; ++k) p[static_cast<size_t>(idx[k])] = v[static_cast<size_t>(k)];
  return p;
}

}  // namespace

PrintedTable1 printed_table1() {
  return {{{{1.0325, 3.1045, 4.8055}, {1.0362, 3.0796, 4.8413}, {1.0888, 3.0651, 4.7880}}},
          {{{1.0661, 3.0797, 4.7974}, {1.0652, 3.0798, 4.7971}, {1.0663, 3.0800, 4.7966}}}};
}

PrintedTable2 printed_table2() {
  PrintedTable2 t;
  t.initial = {1.00913, 0.97689, 1.02748};
  t.dth[0][0] = {1.00078, 0.99948, 0.99976};
  t.dth[0][1] = {1.00000, 1.00000, 1.00000};
  t.dth[1][0] = {0.99999, 1.00001, 1.00000};
  t.dth[1][1] = {1.00000, 1.00000, 1.00000};
  t.kmrmse_mm[0] = {1.47188e-1, 7.85886e-4};
  t.kmrmse_mm[1] = {1.49488e-3, 1.26624e-5};
  return t;
}

PrintedTable3 printed_table3() {
  PrintedTable3 t;
  t.actual = t.initial = none();
  set_links(t.actual, {1, 1, 1, 244.1, 244.2, 243.5, 243.8, 244.2, 244.2});
  set_links(t.initial, {1.01052, 0.97614, 1.02659, 244, 244, 244, 244, 244, 244});
  for (auto& r : t.result) r = none();
  set_links(t.result[0], {0.99996, 1.00004, 1.00008, 244.08300, 244.19647, 244.49562, 243.78108, 244.21085,
                          244.22065});
  set_links(t.result[1], {1.00001, 1.00000, 1.00001, 244.10012, 244.19818, 244.50038, 243.80393, 244.19883,
                          244.20262});
  set_links(t.result[2], {1.00000, 1.00000, 1.00000, 244.09994, 244.19999, 244.49998, 243.79992, 244.20004,
                          244.20006});
  t.kmrmse_mm = {3.21669e-3, 1.56383e-3, 1.33563e-5};
  t.iterations = {46, 47, 33};
  return t;
}

PrintedTable4 printed_table4() {
  PrintedTable4 t;
  t.actual = t.initial = t.twelve = t.eleven = none();
  set_links(t.actual, {1, 1, 1, 244.1, 244.2, 243.5, 243.8, 244.2, 244.2});
  t.actual[kXa3] = 433.05; t.actual[kYa3] = 499.96; t.actual[kXa2] = 433.04;
  set_links(t.initial, {1.01052, 0.97612, 1.02678, 244, 244, 244, 244, 244, 244});
  t.initial[kXa3] = 433; t.initial[kYa3] = 500; t.initial[kXa2] = 433;
  set_links(t.twelve, {1.0072, 1.0072, 1.0072, 244.0998, 247.1998, 247.3005, 246.8959, 244.3009, 244.3005});
  t.twelve[kXa3] = 436.7084; t.twelve[kYa3] = 506.2960; t.twelve[kXa2] = 440.3557;
  set_links(t.eleven, {1.00000, 1.00000, 1.00000, 244.0999, 244.2000, 244.4999, 243.7999, 244.1999, 244.2001});
  t.eleven[kXa3] = 433.0502; t.eleven[kYa3] = 499.9598;
  return t;
}

PrintedTable7 printed_table7() {
  PrintedTable7 t;
  t.actual = section4({0.3, 433.5, 499.4, 244.1, 244.2, 243.5, 243.8, 244.2, 244.6, 0.01, -0.01, 0.01});
  t.de = section4({0.3076, 433.1470, 499.6045, 244.0004, 244.1004, 243.4006, 243.7005, 244.1004, 244.5002, 0.0107,
                   -0.0092, 0.0107});
  return t;
}

PrintedTable8 printed_table8() {
  PrintedTable8 t;
  t.nominal = section4({0, 433, 500, 244, 244, 244, 244, 244, 244, 0, 0, 0});
  t.calibrated = section4({2.7571, 436.2436, 501.9123, 243.6527, 242.5634, 242.4579, 243.8194, 243.4168,
                           246.8952, 6.2385e-3, 1.0623e-2, 2.8643e-3});
  return t;
}

std::array<std::array<double, 3>, 3> printed_figure_finals() {
  return {{{1.3477e3, 2.6869e2, 2.5351e-3},
           {kNotPrinted, kNotPrinted, 5.5626e-14},
           {kNotPrinted, kNotPrinted, 3.5946e-20}}};
}

}  // namespace gpm::calib
