// Times Pinocchio's CRBA, RNEA, ABA (and NLE) on the UR5 and the Panda (fingers locked), models
// from example-robot-data's URDFs: 1000 precomputed random states (q in U(-pi, pi), v in U(-2, 2),
// a in U(-5, 5), tau = 0 for ABA), median over REPS passes of the mean ns per call; a checksum of
// the outputs is printed so that nothing is optimized away. One JSON object per robot on stdout.
//
// Built twice by `mbd-bench/benches/vs_pinocchio.rs` (flags there):
//   with -DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION the algorithms are the precompiled ones of
//     pip's libpinocchio_default.so (called with Eigen::Ref<const VectorXd>, the types of its
//     explicit instantiations);
//   without it every algorithm is instantiated from the headers here, compiled -O3
//     -march=native (with -DEIGEN_MAX_ALIGN_BYTES=16 -DEIGEN_MALLOC_ALREADY_ALIGNED=1, so that
//     objects built by the pip parser library can be freed here).
// Usage: pinocchio_bench <robots dir of example-robot-data> [finger lock, m]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "pinocchio/algorithm/aba.hpp"
#include "pinocchio/algorithm/crba.hpp"
#include "pinocchio/algorithm/joint-configuration.hpp"
#include "pinocchio/algorithm/model.hpp"
#include "pinocchio/algorithm/rnea.hpp"
#include "pinocchio/multibody.hpp"
#include "pinocchio/parsers/urdf.hpp"

using Eigen::VectorXd;
using Ref = Eigen::Ref<const VectorXd>;

static double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

template <typename F>
static double time_it(size_t n, int reps, F f, double &checksum) {
  for (int r = 0; r < 10; ++r)
    for (size_t i = 0; i < n; ++i) checksum += f(i);
  std::vector<double> per_call;
  for (int r = 0; r < reps; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < n; ++i) checksum += f(i);
    auto t1 = std::chrono::steady_clock::now();
    per_call.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / double(n));
  }
  return median(per_call);
}

static void bench(const std::string &name, const pinocchio::Model &model) {
  pinocchio::Data data(model);
  const size_t n = 1000;
  const int reps = 301;
  std::mt19937_64 rng(20261130);
  std::uniform_real_distribution<double> uq(-M_PI, M_PI), uv(-2.0, 2.0), ua(-5.0, 5.0);
  std::vector<VectorXd> qs(n), vs(n), as(n);
  for (size_t i = 0; i < n; ++i) {
    qs[i] = VectorXd(model.nq);
    vs[i] = VectorXd(model.nv);
    as[i] = VectorXd(model.nv);
    for (int k = 0; k < model.nq; ++k) qs[i][k] = uq(rng);
    for (int k = 0; k < model.nv; ++k) vs[i][k] = uv(rng);
    for (int k = 0; k < model.nv; ++k) as[i][k] = ua(rng);
  }
  const VectorXd zero = VectorXd::Zero(model.nv);
  const int last = model.nv - 1;
  double c_crba = 0, c_rnea = 0, c_nle = 0, c_aba = 0;
  double t_crba = time_it(n, reps, [&](size_t i) {
    pinocchio::crba(model, data, Ref(qs[i]));
    return data.M(0, 0) + data.M(last - 1, last);
  }, c_crba);
  double t_rnea = time_it(n, reps, [&](size_t i) {
    const VectorXd &tau = pinocchio::rnea(model, data, Ref(qs[i]), Ref(vs[i]), Ref(as[i]));
    return tau[0] + tau[last];
  }, c_rnea);
  double t_nle = time_it(n, reps, [&](size_t i) {
    const VectorXd &h = pinocchio::nonLinearEffects(model, data, Ref(qs[i]), Ref(vs[i]));
    return h[0] + h[last];
  }, c_nle);
  double t_aba = time_it(n, reps, [&](size_t i) {
    const VectorXd &ddq = pinocchio::aba(model, data, Ref(qs[i]), Ref(vs[i]), Ref(zero));
    return ddq[0] + ddq[last];
  }, c_aba);
  std::printf("{\"robot\": \"%s\", \"nq\": %d, \"crba\": %.1f, \"rnea\": %.1f, \"nle\": %.1f, \"aba\": %.1f, "
              "\"checksum\": %.10e}\n",
              name.c_str(), model.nq, t_crba, t_rnea, t_nle, t_aba, c_crba + c_rnea + c_nle + c_aba);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s <example-robot-data robots dir> [finger lock m]\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  const double finger = argc > 2 ? std::atof(argv[2]) : 0.02;
  {
    pinocchio::Model ur5;
    pinocchio::urdf::buildModel(dir + "/ur_description/urdf/ur5_robot.urdf", ur5);
    bench("ur5", ur5);
  }
  {
    pinocchio::Model full;
    pinocchio::urdf::buildModel(dir + "/panda_description/urdf/panda.urdf", full);
    VectorXd q_ref = pinocchio::neutral(full);
    std::vector<pinocchio::JointIndex> lock;
    for (const char *j : {"panda_finger_joint1", "panda_finger_joint2"}) {
      pinocchio::JointIndex id = full.getJointId(j);
      q_ref[full.joints[id].idx_q()] = finger;
      lock.push_back(id);
    }
    pinocchio::Model panda = pinocchio::buildReducedModel(full, lock, q_ref);
    bench("panda", panda);
  }
  return 0;
}
