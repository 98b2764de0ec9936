#include "pbr_reference.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace clpt::test {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double schlick_weight(double c) { return std::pow(std::clamp(1 - c, 0.0, 1.0), 5); }

// The specular lobe's albedo in its two Fresnel parts (E = F0 s + F90 b, s weighted by
// 1 - (1 - o.h)^5 and b by (1 - o.h)^5), integrated in double over the half vector (theta_h =
// atan(alpha tan(v pi / 2)) spreads the grid by the lobe's width); where the kernel makes the
// lobe a delta (alpha < 1e-3), the Fresnel term at cos_o itself.
SpecularParts specular_parts(double cos_o, double roughness, int n) {
  const double alpha = roughness * roughness, a2 = alpha * alpha;
  if (alpha < 1e-3) return {1 - schlick_weight(cos_o), schlick_weight(cos_o)};
  const double so = std::sqrt(1 - cos_o * cos_o);
  SpecularParts sum{0, 0};
  for (int i = 0; i < n; ++i) {
    const double v = (i + 0.5) / n, tv = std::tan(v * kPi / 2);
    const double th = std::atan(alpha * tv), cv = std::cos(v * kPi / 2);
    const double dth = alpha * (kPi / 2) / (cv * cv) / (1 + a2 * tv * tv) / n;
    for (int j = 0; j < 2 * n; ++j) {
      const double ph = (j + 0.5) / (2 * n) * 2 * kPi;
      const double h[3] = {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)};
      const double oh = h[0] * so + h[2] * cos_o;
      if (oh <= 0) continue;
      const double ci = 2 * oh * h[2] - cos_o;
      if (ci <= 0) continue;
      const double k = h[2] * h[2] * (a2 - 1) + 1, d = a2 / (kPi * k * k);
      const double vis = 0.5 / (ci * std::sqrt(a2 + (1 - a2) * cos_o * cos_o) + cos_o * std::sqrt(a2 + (1 - a2) * ci * ci));
      const double f = d * vis * ci * 4 * oh * std::sin(th) * dth * (kPi / n);  // d omega_i = 4 (o.h) d omega_h
      sum.s += f * (1 - schlick_weight(oh));
      sum.b += f * schlick_weight(oh);
    }
  }
  return sum;
}

// The white metal's albedo: f = D V Schlick(F0 = 1) = D V.
double white_metal_albedo(double cos_o, double roughness) {
  const SpecularParts p = specular_parts(cos_o, roughness);
  return p.s + p.b;
}

// The mean of (1 - o.h)^5 over wi distributed as cos / pi, by the midpoint rule over (cos_i, phi).
double fresnel_mean(double cos_o, int n) {
  const double so = std::sqrt(1 - cos_o * cos_o);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double ci = (i + 0.5) / n, si = std::sqrt(1 - ci * ci);
    for (int j = 0; j < 2 * n; ++j) {
      const double ph = (j + 0.5) / (2 * n) * 2 * kPi;
      const double h[3] = {so + si * std::cos(ph), si * std::sin(ph), cos_o + ci};
      const double len = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
      sum += schlick_weight((so * h[0] + cos_o * h[2]) / len) * ci / kPi * (1.0 / n) * (kPi / n);
    }
  }
  return sum;
}

namespace {

struct Lobe {
  double specular, fresnel_dielectric, fresnel_metal;
};
Lobe lobe_at(const Material1& m, const double wo[3], const double wi[3]) {
  double h[3] = {wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]};
  const double len = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  for (double& c : h) c /= len;
  const double a2 = std::pow(m.roughness, 4), oh = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2];
  const double k = h[2] * h[2] * (a2 - 1) + 1, d = a2 / (kPi * k * k);
  const double vis = 0.5 / (wi[2] * std::sqrt(a2 + (1 - a2) * wo[2] * wo[2]) + wo[2] * std::sqrt(a2 + (1 - a2) * wi[2] * wi[2]));
  const double f0 = std::pow((m.ior - 1) / (m.ior + 1), 2), w = schlick_weight(oh);
  return {d * vis, f0 + (1 - f0) * w, m.base + (1 - m.base) * w};
}
}  // namespace

double appendix_b_f(const Material1& m, const double wo[3], const double wi[3]) {
  const Lobe l = lobe_at(m, wo, wi);
  const double dielectric = l.specular * l.fresnel_dielectric + (1 - l.fresnel_dielectric) * m.base / kPi;
  return (1 - m.metallic) * dielectric + m.metallic * l.specular * l.fresnel_metal;
}
double clpt_f(const Material1& m, const double wo[3], const double wi[3]) {
  // The quadratures depend on (cos_o, roughness) alone: integrated once for the cases sharing them.
  static std::map<std::pair<double, double>, std::pair<SpecularParts, double>> integrated;
  auto it = integrated.find({wo[2], m.roughness});
  if (it == integrated.end())
    it = integrated.emplace(std::make_pair(wo[2], m.roughness),
                            std::make_pair(specular_parts(wo[2], m.roughness, 300), fresnel_mean(wo[2], 200))).first;
  const Lobe l = lobe_at(m, wo, wi);
  const SpecularParts e = it->second.first;
  const double f0 = std::pow((m.ior - 1) / (m.ior + 1), 2), albedo = f0 * e.s + e.b;
  const double scale = (1 - albedo) / (1 - (f0 + (1 - f0) * it->second.second));
  const double dielectric = l.specular * l.fresnel_dielectric + (1 - l.fresnel_dielectric) * scale * m.base / kPi;
  return (1 - m.metallic) * dielectric + m.metallic * l.specular * l.fresnel_metal;
}

}  // namespace clpt::test
