// The covering set of kernel variants: a few kernel configurations that together contain every
// value of every dimension that changes what a kernel compiles (execution form and megakernel
// loop, precision, estimator, Russian roulette, specialised or generic, the specialised loops
// unrolled or rolled, each material present or absent, spheres alone or a mesh and a hierarchy,
// the glTF material with or without transmission, each punctual light kind, the camera's
// projection, the environment light (none, an image or a constant), the first-hit layers of
// --aovs) and every pair of values of two dimensions that can be rendered together (the book
// estimator refuses punctual lights). Two test tiers use the same set:
//   oclgrind  renders each on Oclgrind with its memory, race and API checks, and against PoCL
//   gpucc     compiles each for NVIDIA (nvptx64) and AMD (amdgcn) with clang and libclc
//             (`clpt kernels emit` writes their sources and build options)
// A later feature that changes what kernels compile adds its dimension to
// kernel_variant_dimensions() (and its effect to apply_variant / variant_program); both tiers
// then cover it, alone and in pairs, with no other change.
#pragma once

#include <string>
#include <vector>

#include "kernels/kernel_options.h"
#include "render/render_request.h"
#include "scene/scene.h"

namespace clpt {

// One dimension and its values, as variant names spell them.
struct VariantDimension {
  std::string name;
  std::vector<std::string> values;
};

// The dimensions, in the order of KernelVariant::choice.
const std::vector<VariantDimension>& kernel_variant_dimensions();

struct KernelVariant {
  std::vector<int> choice;  // per dimension, the index of its value

  ExecutionForm form() const;
  MegakernelLoop megakernel_loop() const;  // PerPath or Lockstep; PerPath for the wavefront
  Precision precision() const;
  Estimator estimator() const;
  bool russian_roulette() const;
  bool generic() const;
  SceneLoops scene_loops() const;  // Unrolled or Rolled (a generic kernel has no fixed loops)
  bool has_phong() const;  // the scene has a Phong ball
  bool has_glass() const;  // the scene has a glass ball
  // The scene has a mesh (a mirror octahedron) and 12 pebbles more: the kernel traverses a
  // hierarchy of triangles and spheres (with the book's balls) instead of only the sphere loop.
  bool has_mesh() const;
  bool has_pbr() const;               // a ball of the glTF material
  bool has_pbr_transmission() const;  // that ball transmits (thin-walled, and emits; or a volume)
  bool has_pbr_volume() const;        // that ball is a volume (thickness > 0): refraction, Beer's law
  int punctual_light() const;         // 0 none, 1 point, 2 spot, 3 directional
  bool orthographic() const;          // the camera's projection
  int environment() const;            // 0 none, 1 an image (16 x 8 sky with a sun), 2 a constant colour
  bool aovs() const;                  // the first-hit layers (--aovs: CLPT_AOVS)
  int textures() const;               // 0 none, 1 a tile with every storage and map kind (docs/textures.md),
                                      // 2 that tile with vertex colours (glTF COLOR_0), 3 textured
                                      // spheres (the left ball, the light, the glTF ball)

  // The values joined by '.', e.g. "megakernel-lockstep.robust.nee.rr.specialised.unrolled.phong.no-glass";
  // usable as a file name and a test name (after replacing '.' and '-').
  std::string name() const;
};

// Every value of every dimension and every pair of values of two dimensions, each in at least
// one variant (greedy: each variant covers as many uncovered pairs as any candidate can).
// Deterministic: the same list on every machine and run.
std::vector<KernelVariant> covering_kernel_variants();

// The length of the shortest prefix of `variants` that holds every value of every dimension (the
// covering set's first few do: the greedy picks the variants that cover the most pairs first).
// The Oclgrind tier's default run renders that prefix; the rest of the set (every pair) runs
// under the label oclgrind-pairs (docs/oclgrind.md). variants.size() when no prefix holds them all.
size_t value_covering_prefix(const std::vector<KernelVariant>& variants);

// Pairs of values (of two different dimensions) that `variants` leaves uncovered, as
// "dimension=value + dimension=value" strings; empty when the set covers every pair.
std::vector<std::string> uncovered_pairs(const std::vector<KernelVariant>& variants);

// The variant's scene from the book's diffuse scene (scenes/diffuse.toml): its left ball becomes
// the specular scene's Phong material and its right ball the glass scene's glass when the
// variant has them; a mesh variant adds a mirror octahedron on the floor and 12 pebbles (so that
// triangles and spheres are hierarchy primitives); a pbr variant a ball of the glTF material
// between them; a light variant one punctual light in the room; an orthographic variant that
// camera, 6 units high; an environment variant a small sky image or a constant colour, seen
// through the room's open front; its estimator and Russian roulette (from bounce 2) are set from the
// variant.
// Throws Error(Failure) when the scene has no spheres named left_ball and right_ball.
Scene variant_scene(const Scene& diffuse, const KernelVariant& variant);

// Sets the request's form, loop, precision and kernel specialisation to the variant's, and its
// scene to variant_scene(request.scene, variant).
void apply_variant(const KernelVariant& variant, RenderRequest& request);

// The program a variant builds: the kernel file and the features (the lockstep loop resolved to
// its default work-group), exactly as a render of variant_scene() on a device would build it.
struct VariantProgram {
  std::string entry_file;  // "megakernel.cl" or "wavefront.cl"
  KernelFeatures features;
};
VariantProgram variant_program(const Scene& variant_scene, const KernelVariant& variant);

}  // namespace clpt
