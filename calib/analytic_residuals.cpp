#include "calib/analytic_residuals.hpp"

#include <cmath>

#include "models/closure.hpp"

namespace gpm::calib {

ReadingTrig::ReadingTrig(const Eigen::Vector3d& theta_m) {
  for (int i = 0; i < 3; ++i) c[i] = std::cos(theta_m[i]), s[i] = std::sin(theta_m[i]);
}

namespace {

// Local parameter m of chain k: xa, ya, la (or l_ac), dth (or l_as), lb.
constexpr int kChainParams = 5;
constexpr int param_of(int k, int m) {
  return m == 0 ? xa(k) : m == 1 ? ya(k) : m == 2 ? la(k) : m == 3 ? dth(k) : lb(k);
}

// cos and sin of the three encoder offsets, remembered per thread: LM
// evaluates every sample at the same parameters in turn, so all but the first
// sample of a sweep reuse them.
void offset_trig(const double* x, double c[3], double s[3]) {
  thread_local double last[3] = {NAN, NAN, NAN}, lc[3], ls[3];
  for (int i = 0; i < 3; ++i) {
    if (!(x[dth(i)] == last[i])) {
      last[i] = x[dth(i)];
      lc[i] = std::cos(last[i]);
      ls[i] = std::sin(last[i]);
    }
    c[i] = lc[i];
    s[i] = ls[i];
  }
}

// The closure of one sample: base joints, elbows (eq. 30 and 35, or eq. 41
// decoupled) and the radical centre of models/closure.hpp.
struct Loop {
  double Ax[3], Ay[3], Bx[3], By[3];
  double ca[3], sa[3];  // direction of the active link (coupled) or of theta_m (decoupled)
  RadicalCentre<double> rc;
};

// Fills L; false when the elbows are collinear (no radical centre).
bool loop_of(const double* x, const ReadingTrig& t, bool decoupled, Loop& L) {
  if (decoupled) {
    for (int i = 0; i < 3; ++i) L.ca[i] = t.c[i], L.sa[i] = t.s[i];
  } else {
    double cd[3], sd[3];
    offset_trig(x, cd, sd);
    for (int i = 0; i < 3; ++i) {  // theta_a = theta_m + dth (eq. 35)
      L.ca[i] = t.c[i] * cd[i] - t.s[i] * sd[i];
      L.sa[i] = t.s[i] * cd[i] + t.c[i] * sd[i];
    }
  }
  double lb_[3];
  for (int i = 0; i < 3; ++i) {
    L.Ax[i] = x[xa(i)];
    L.Ay[i] = x[ya(i)];
    lb_[i] = x[lb(i)];
    if (decoupled) {  // eq. 41
      L.Bx[i] = L.Ax[i] + x[la(i)] * L.ca[i] - x[dth(i)] * L.sa[i];
      L.By[i] = L.Ay[i] + x[la(i)] * L.sa[i] + x[dth(i)] * L.ca[i];
    } else {  // eq. 30
      L.Bx[i] = L.Ax[i] + x[la(i)] * L.ca[i];
      L.By[i] = L.Ay[i] + x[la(i)] * L.sa[i];
    }
  }
  L.rc = radical_centre(L.Bx, L.By, lb_);
  return L.rc.ok;
}

// First-order sensitivities of a loop (header comment): for a unit right-hand
// side at chain k, dO = o[k] and dP = q[k]; parameter m of chain k moves B_k
// by dB[k][m] with right-hand side s[k][m].
struct Sensitivity {
  double o[3][2];
  double q[3];
  double dB[3][kChainParams][2];
  double s[3][kChainParams];
};

void sensitivity(const double* x, const Loop& L, bool decoupled, Sensitivity& S) {
  const RadicalCentre<double>& r = L.rc;
  for (int k = 0; k < 3; ++k) {
    const double rhs2 = (k == 1 ? 1.0 : 0.0) - (k == 0 ? 1.0 : 0.0);
    const double rhs3 = (k == 2 ? 1.0 : 0.0) - (k == 0 ? 1.0 : 0.0);
    S.o[k][0] = -(rhs2 * r.d3y - rhs3 * r.d2y) / (2.0 * r.det);
    S.o[k][1] = -(r.d2x * rhs3 - r.d3x * rhs2) / (2.0 * r.det);
    S.q[k] = 2.0 * (r.ux * S.o[k][0] + r.uy * S.o[k][1]) - (k == 0 ? 1.0 : 0.0);
  }
  for (int k = 0; k < 3; ++k) {
    // dB_k / d(la slot) and dB_k / d(dth slot)
    const double el0 = L.ca[k], el1 = L.sa[k];
    const double ed0 = decoupled ? -L.sa[k] : -(L.By[k] - L.Ay[k]);
    const double ed1 = decoupled ? L.ca[k] : L.Bx[k] - L.Ax[k];
    const double dB[kChainParams][2] = {{1, 0}, {0, 1}, {el0, el1}, {ed0, ed1}, {0, 0}};
    const double wx = r.Ox - L.Bx[k], wy = r.Oy - L.By[k];
    for (int m = 0; m < kChainParams; ++m) {
      S.dB[k][m][0] = dB[m][0], S.dB[k][m][1] = dB[m][1];
      S.s[k][m] = m == 4 ? 2.0 * x[lb(k)] : 2.0 * (wx * dB[m][0] + wy * dB[m][1]);
    }
  }
}

}  // namespace

bool E1Analytic::Evaluate(double const* const* params, double* res, double** jac) const {
  const double* x = params[0];
  Loop L;
  if (!loop_of(x, trig_, false, L)) return false;
  double w[3][2], n[3];
  for (int i = 0; i < 3; ++i) {
    w[i][0] = L.rc.Ox - L.Bx[i], w[i][1] = L.rc.Oy - L.By[i];
    n[i] = std::sqrt(w[i][0] * w[i][0] + w[i][1] * w[i][1]);
    if (!(n[i] > 0.0)) return false;
    res[i] = n[i] - x[lb(i)];
  }
  if (!jac || !jac[0]) return true;
  Sensitivity S;
  sensitivity(x, L, false, S);
  double u[3][2];  // w_i / |w_i|
  for (int i = 0; i < 3; ++i) u[i][0] = w[i][0] / n[i], u[i][1] = w[i][1] / n[i];
  double* J = jac[0];
  for (int k = 0; k < 3; ++k) {
    for (int m = 0; m < kChainParams; ++m) {
      const int p = param_of(k, m);
      const double dOx = S.s[k][m] * S.o[k][0], dOy = S.s[k][m] * S.o[k][1];
      for (int i = 0; i < 3; ++i) {
        const double dwx = dOx - (i == k ? S.dB[k][m][0] : 0.0);
        const double dwy = dOy - (i == k ? S.dB[k][m][1] : 0.0);
        J[i * kNumParams + p] = u[i][0] * dwx + u[i][1] * dwy - (i == k && m == 4 ? 1.0 : 0.0);
      }
    }
  }
  return true;
}

bool PowerAnalytic::Evaluate(double const* const* params, double* res, double** jac) const {
  const double* x = params[0];
  Loop L;
  if (!loop_of(x, trig_, decoupled_, L)) return false;
  res[0] = L.rc.P;
  if (!jac || !jac[0]) return true;
  Sensitivity S;
  sensitivity(x, L, decoupled_, S);
  for (int k = 0; k < 3; ++k)
    for (int m = 0; m < kChainParams; ++m) jac[0][param_of(k, m)] = S.s[k][m] * S.q[k];
  return true;
}

bool MlAnalytic::Evaluate(double const* const* params, double* res, double** jac) const {
  const double* x = params[0];
  Loop L;
  if (!loop_of(x, trig_, false, L)) return false;
  // g = dP/d theta_m needs q, so the sensitivities are needed for the residual too.
  Sensitivity S;
  sensitivity(x, L, false, S);
  double w[3][2], t[3][2], b[3], g[3];
  double g2 = 0.0;
  for (int j = 0; j < 3; ++j) {
    w[j][0] = L.rc.Ox - L.Bx[j], w[j][1] = L.rc.Oy - L.By[j];
    t[j][0] = -(L.By[j] - L.Ay[j]), t[j][1] = L.Bx[j] - L.Ax[j];  // perp(B_j - A_j)
    b[j] = 2.0 * (w[j][0] * t[j][0] + w[j][1] * t[j][1]);
    g[j] = S.q[j] * b[j];
    g2 += g[j] * g[j];
  }
  if (!(g2 > 0.0)) return false;
  const double gn = std::sqrt(g2);
  res[0] = L.rc.P / gn;
  if (!jac || !jac[0]) return true;
  for (int k = 0; k < 3; ++k) {
    for (int m = 0; m < kChainParams; ++m) {
      const double sp = S.s[k][m];
      const double dOx = sp * S.o[k][0], dOy = sp * S.o[k][1];
      const double dP = sp * S.q[k];
      const double* dB = S.dB[k][m];
      const double dA[2] = {m == 0 ? 1.0 : 0.0, m == 1 ? 1.0 : 0.0};  // d A_k / d p
      const double vx = -dOx - S.q[k] * dB[0], vy = -dOy - S.q[k] * dB[1];
      double g_dg = 0.0;
      for (int j = 0; j < 3; ++j) {
        const double dq = -2.0 * (vx * S.o[j][0] + vy * S.o[j][1]);
        const double dwx = dOx - (j == k ? dB[0] : 0.0), dwy = dOy - (j == k ? dB[1] : 0.0);
        double db = 2.0 * (dwx * t[j][0] + dwy * t[j][1]);
        if (j == k) {
          // perp(dB - dA) = (-(dBy - dAy), dBx - dAx)
          db += 2.0 * (w[j][0] * -(dB[1] - dA[1]) + w[j][1] * (dB[0] - dA[0]));
        }
        g_dg += g[j] * (dq * b[j] + S.q[j] * db);
      }
      jac[0][param_of(k, m)] = dP / gn - L.rc.P * g_dg / (g2 * gn);
    }
  }
  return true;
}

ceres::CostFunction* make_analytic_residual(Cost c, const Eigen::Vector3d& theta_m) {
  switch (c) {
    case Cost::kJ1: return new E1Analytic(theta_m);
    case Cost::kJ2: return new PowerAnalytic(theta_m, false);
    case Cost::kJ3: return new PowerAnalytic(theta_m, true);
    case Cost::kML: return new MlAnalytic(theta_m);
  }
  return nullptr;
}

}  // namespace gpm::calib
