// Build step: writes kernels' pbr_albedo_table.h, the directional albedo of the glTF material's
// specular layer that its base layer is scaled by (kernels/bsdf_pbr.cl, docs/materials.md
// "The base layer"), integrated in double once, when clpt is built.
//
//   make_pbr_albedo_table OUTPUT
//
// For the GGX lobe of bsdf_pbr.cl (D with alpha = roughness^2, height-correlated Smith V) and
// Schlick's Fresnel F = F0 + (F90 - F0) (1 - o.h)^5, the albedo at cos_o = mu is linear in F0
// and F90:  E(mu) = F0 S(mu, r) + F90 B(mu, r)  with
//   S = integral of D V (1 - (1 - o.h)^5) cos_i  and  B = integral of D V (1 - o.h)^5 cos_i
// over the hemisphere of wi. Where bsdf_pbr.cl makes the lobe a delta (alpha < 1e-3) the albedo
// is the Fresnel term at mu itself: S = 1 - (1 - mu)^5, B = (1 - mu)^5. Also the mean of the
// Fresnel weight of the half vector over cosine-distributed wi, which Appendix B's fresnel_mix
// removes from a Lambertian base:  G(mu) = integral of (1 - o.h)^5 cos_i / pi.
//
// Grid: mu = t^2 and roughness = s^2 for t, s uniform in [0, 1] (both sharpen near 0: grazing
// views and narrow lobes), CLPT_PBR_ALBEDO_NMU points in t and CLPT_PBR_ALBEDO_NR in s; 16 KB. tests/test_pbr_bsdf.cpp checks the
// table, through the kernel's lookup, against its own quadrature.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

constexpr int kNmu = 64, kNr = 32;
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeltaAlpha = 1e-3;  // CLPT_PBR_DELTA_ALPHA in bsdf_pbr.cl

double schlick_weight(double c) {
  const double m = std::clamp(1 - c, 0.0, 1.0);
  return m * m * m * m * m;
}

// S and B at (mu, roughness): over the half vector, theta_h = atan(alpha tan(v pi / 2)) spreading
// the midpoint grid by the lobe's width, d omega_i = 4 (o.h) d omega_h; phi over [0, pi] twice
// (the lobe is symmetric about wo's plane).
void specular_albedo(double mu, double roughness, double* s, double* b) {
  const double alpha = roughness * roughness;
  if (alpha < kDeltaAlpha) {
    *s = 1 - schlick_weight(mu);
    *b = schlick_weight(mu);
    return;
  }
  const double a2 = alpha * alpha, so = std::sqrt(std::max(0.0, 1 - mu * mu));
  constexpr int kTheta = 512, kPhi = 256;
  double sum_s = 0, sum_b = 0;
  for (int i = 0; i < kTheta; ++i) {
    const double v = (i + 0.5) / kTheta, tv = std::tan(v * kPi / 2), cv = std::cos(v * kPi / 2);
    const double th = std::atan(alpha * tv);
    const double dth = alpha * (kPi / 2) / (cv * cv) / (1 + a2 * tv * tv) / kTheta;
    const double ch = std::cos(th), sh = std::sin(th);
    const double k = ch * ch * (a2 - 1) + 1, d = a2 / (kPi * k * k);
    for (int j = 0; j < kPhi; ++j) {
      const double ph = (j + 0.5) / kPhi * kPi;
      const double oh = sh * std::cos(ph) * so + ch * mu;
      if (oh <= 0) continue;
      const double ci = 2 * oh * ch - mu;
      if (ci <= 0) continue;
      const double vis = 0.5 / (ci * std::sqrt(a2 + (1 - a2) * mu * mu) + mu * std::sqrt(a2 + (1 - a2) * ci * ci));
      const double f = d * vis * ci * 4 * oh * sh * dth * (2 * kPi / kPhi);
      const double w = schlick_weight(oh);
      sum_s += f * (1 - w);
      sum_b += f * w;
    }
  }
  *s = sum_s;
  *b = sum_b;
}

// G(mu): over wi in (cos theta_i, phi), midpoint (the integrand is smooth).
double fresnel_mean(double mu) {
  const double so = std::sqrt(std::max(0.0, 1 - mu * mu));
  constexpr int kCos = 512, kPhi = 256;
  double sum = 0;
  for (int i = 0; i < kCos; ++i) {
    const double ci = (i + 0.5) / kCos, si = std::sqrt(1 - ci * ci);
    for (int j = 0; j < kPhi; ++j) {
      const double ph = (j + 0.5) / kPhi * kPi;
      const double h[3] = {so + si * std::cos(ph), si * std::sin(ph), mu + ci};
      const double len = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
      const double oh = len > 0 ? (so * h[0] + mu * h[2]) / len : 1;
      sum += schlick_weight(oh) * ci / kPi * (1.0 / kCos) * (2 * kPi / kPhi);
    }
  }
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_pbr_albedo_table OUTPUT\n");
    return 2;
  }
  std::string text =
      "/* pbr_albedo_table.h: generated when clpt is built, by cmake/make_pbr_albedo_table.cpp. Do not edit.\n"
      " * clpt_pbr_albedo[(j * NMU + i) * 2 + {0, 1}] = S, B at mu = (i / (NMU - 1))^2, roughness = (j / (NR - 1))^2;\n"
      " * clpt_pbr_fresnel_mean[i] = G at the same mu (bsdf_pbr.cl says how they are used). */\n"
      "#ifndef CLPT_PBR_ALBEDO_TABLE_H\n#define CLPT_PBR_ALBEDO_TABLE_H\n";
  text += "#define CLPT_PBR_ALBEDO_NMU " + std::to_string(kNmu) + "\n#define CLPT_PBR_ALBEDO_NR " + std::to_string(kNr) + "\n";
  text += "__constant float clpt_pbr_albedo[" + std::to_string(kNmu * kNr * 2) + "] = {\n";
  char buf[64];
  for (int j = 0; j < kNr; ++j) {
    const double sr = double(j) / (kNr - 1);
    for (int i = 0; i < kNmu; ++i) {
      const double t = double(i) / (kNmu - 1);
      double s, b;
      specular_albedo(std::max(t * t, 1e-6), sr * sr, &s, &b);
      std::snprintf(buf, sizeof buf, "%.8ef, %.8ef,%s", s, b, i % 4 == 3 ? "\n" : " ");
      text += buf;
    }
  }
  text += "};\n__constant float clpt_pbr_fresnel_mean[" + std::to_string(kNmu) + "] = {\n";
  for (int i = 0; i < kNmu; ++i) {
    const double t = double(i) / (kNmu - 1);
    std::snprintf(buf, sizeof buf, "%.8ef,%s", fresnel_mean(std::max(t * t, 1e-6)), i % 8 == 7 ? "\n" : " ");
    text += buf;
  }
  text += "};\n#endif\n";
  const std::string tmp = std::string(argv[1]) + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f || std::fwrite(text.data(), 1, text.size(), f) != text.size() || std::fclose(f) != 0 ||
      std::rename(tmp.c_str(), argv[1]) != 0) {
    std::fprintf(stderr, "make_pbr_albedo_table: cannot write %s\n", argv[1]);
    return 1;
  }
  return 0;
}
