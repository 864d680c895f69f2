#pragma once
// ProfileRenderer's beam plane, shared by its translation units (profile_renderer.cpp: the
// ping; profile_line_march.cpp: the march; profile_target_rays.cpp: the target rays). Not part of
// the renderer's interface.
#include <vector>

#include "sim/render/profile_renderer.h"
#include "sim/seabed/height_sampler.h"

namespace sonarloop::render {

// The heightfield march of one beam plane (profile renderer): per sample, what the horizon and
// target tests need. Sized once, reused.
struct ProfileLineScratch {
  std::vector<float> edge_tan;  // target rays: in-plane tan(depression) of each tube edge
  std::vector<float> ray_tan;   // target rays: in-plane tan(depression) of the ray
  std::vector<float> ray_s;     // target rays: in-plane ground distance of the hit
  std::vector<float> hit_r;     // target rays: hit range (inf: no hit)
  std::vector<float> horizon;   // running minimum tan(depression) after each march sample
};

// The profile renderer's own buffers of one rendering thread (PingScratch::own).
struct ProfileScratch final : RendererScratch {
  ProfileLineScratch line;
  seabed::HeightSampler heights;  // heightmap tiles of the scene being rendered
};

// One beam plane of a ping (see the header for the frame).
struct ProfileRenderer::Line {
  int side = 0;
  double sign = 1.0;
  const Mat3* R = nullptr;
  int j = 0;
  Vec3 o = Vec3::Zero();  // transducer, world
  Vec3 n = Vec3::Zero();  // vehicle x axis (normal of the plane)
  Vec3 u = Vec3::Zero();  // horizontal, across track towards this side
  Vec3 w = Vec3::Zero();  // in the plane, below u (w.z = cos(pitch) > 0)
  bool strip = true;
  double alpha = 0.0;  // strip: offset of the plane along n (m)
  double sin_psi = 0.0;
  double inv_cos_psi = 1.0;
  double weight = 0.0;  // along-track weight W (strip: m; beam: rad, times r)
  double pat_a = 0.0;   // sin(off axis) = (s·pat_a + β·pat_b) / ρ
  double pat_b = 0.0;
  double altitude = 0.0;
  double depth = 0.0;  // world z of elevation 0
  double s_start = 0.0;
  double step = 0.0;
  int samples = 0;
  double r_start = 0.0;  // fan: first vertical edge's flat-seabed range
  double r_max = 0.0;    // end of the window (target rays' length)
};

}  // namespace sonarloop::render
