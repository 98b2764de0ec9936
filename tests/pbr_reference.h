// The glTF material on the host, in double: the references the Pbr tests check the device
// against (test_pbr_bsdf.cpp, test_pbr_render.cpp). Two models of one grey-based material: the
// glTF specification's Appendix B as written, and clpt's (docs/materials.md "The base layer":
// Appendix B's fresnel_mix scaled by the specular layer's albedo), with the albedo integrated
// here independently of the table the kernels read (cmake/make_pbr_albedo_table.cpp).
#pragma once

namespace clpt::test {

// (1 - c)^5, c clamped to [0, 1]: Schlick's weight.
double schlick_weight(double c);

// The specular lobe's albedo at cos_o in its two Fresnel parts: E = F0 s + F90 b, s weighted by
// 1 - (1 - o.h)^5 and b by (1 - o.h)^5, integrated over the half vector on an n x 2n grid; where
// the kernel makes the lobe a delta (alpha = roughness^2 < 1e-3), the Fresnel term at cos_o.
struct SpecularParts {
  double s, b;
};
SpecularParts specular_parts(double cos_o, double roughness, int n = 600);

// The white metal's albedo (F0 = 1: f = D V): s + b.
double white_metal_albedo(double cos_o, double roughness);

// The mean of (1 - o.h)^5 over wi distributed as cos / pi (midpoint rule on an n x 2n grid).
double fresnel_mean(double cos_o, int n = 400);

// A material with a grey base colour; wo and wi in the local frame (z the normal), both above.
struct Material1 {
  double base, metallic, roughness, ior = 1.5;
};
// f(wo, wi) as Appendix B writes it: mix(fresnel_mix(ior, base / pi, D V), D V Schlick(base), metallic).
double appendix_b_f(const Material1& m, const double wo[3], const double wi[3]);
// f(wo, wi) as clpt renders it: fresnel_mix's base layer times (1 - E(n.wo)) / (1 - Fmean(n.wo)).
// The quadratures are cached per (cos_o, roughness).
double clpt_f(const Material1& m, const double wo[3], const double wi[3]);

}  // namespace clpt::test
