#include "sim/render/profile_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/render/bin_labels.h"
#include "sim/render/echo_model.h"
#include "sim/render/profile_line.h"

namespace sonarloop::render {
namespace {

// A segment steeper than this many bins of slant range (a rock's flank seen end-on) is cut at
// that many bin edges and its rest goes to the last bin.
constexpr int kMaxPiecesPerSegment = 64;
// Echo terms changing by more than this fraction along a segment are interpolated by a
// quadratic through the segment's middle (see march()).
constexpr double kCurvedEcho = 0.01;

// [lo, hi] ∩ {s : a + s·b inside [min, max]} (one axis of a slab clip)
void clip_axis(double a, double b, double min, double max, double& lo, double& hi) {
  if (std::abs(b) < 1e-12) {
    if (a < min || a > max) hi = lo - 1.0;  // empty
    return;
  }
  double t0 = (min - a) / b;
  double t1 = (max - a) / b;
  if (t0 > t1) std::swap(t0, t1);
  lo = std::max(lo, t0);
  hi = std::min(hi, t1);
}

}  // namespace

ProfileRenderer::ProfileRenderer(const SonarSetup& sonar, const Fidelity& fidelity)
    : PingRenderer(sonar, fidelity) {}

void ProfileRenderer::prepare(const scene::Scene& scene, const Pose& pose,
                              const RenderOptions& options, PingScratch& /*scratch*/) const {
  const seabed::SeabedModel& sb = scene.seabed();
  const MarchPlan plan = march_plan(fidelity_, sb.spacing_m(), sonar_.desc.bin_size_m);
  scene.target_bvh();
  // the tiles along each side's ground line, at half a tile's width apart
  const double r = std::min(options.range_max_m, sonar_.desc.max_range_m);
  const double tile_m = sb.tile_size() * plan.spacing_m;
  const Vec3 n = pose.R_WV().col(0);
  const double h = std::hypot(n.x(), n.y());
  const Vec2 along = h > 1e-6 ? Vec2(n.x() / h, n.y() / h) : heading_vector(pose.yaw);
  const Vec2 across(-along.y(), along.x());
  const Vec2 lo = sb.extent_min();
  const Vec2 hi = sb.extent_max();
  // tiles another thread is making are left to it: work ahead never waits
  const auto tile_of = [&](double v) {
    return sb.tile_of(static_cast<std::int64_t>(std::floor(v / plan.spacing_m)));
  };
  for (int side = 0; side < 2; ++side) {
    if (!(options.side_mask & (1 << side))) continue;
    const double sign = side == 0 ? -1.0 : 1.0;
    for (double s = 0.0; s <= r + 0.5 * tile_m; s += 0.5 * tile_m) {
      const Vec2 p = pose.position_W.head<2>() + sign * std::min(s, r) * across;
      if (p.x() < lo.x() || p.y() < lo.y() || p.x() > hi.x() || p.y() > hi.y()) continue;
      sb.prefetch_tile(tile_of(p.x()), tile_of(p.y()), plan.level);
    }
  }
}

void ProfileRenderer::render(const scene::Scene& scene, const Pose& pose, std::uint64_t seed,
                             std::uint64_t ping_index, const RenderOptions& options,
                             PingScratch& scratch, PingLines& out) const {
  scratch.traces.clear();
  scratch.rays_cast = 0;
  scratch.samples = 0;
  echo().start_lines(options, scratch);
  const seabed::SeabedModel& sb = scene.seabed();
  const MarchPlan plan = march_plan(fidelity_, sb.spacing_m(), sonar_.desc.bin_size_m);
  scratch.heights.bind(sb, plan.level);
  const Vec3 o = pose.position_W;

  // altitude: the heightfield below the sonar, or a target straight below it
  double altitude = options.nadir_altitude_m;
  const scene::TargetBvh& bvh = scene.target_bvh();
  if (std::isnan(altitude)) {
    const Vec2 lo = sb.extent_min();
    const Vec2 hi = sb.extent_max();
    if (o.x() >= lo.x() && o.y() >= lo.y() && o.x() <= hi.x() && o.y() <= hi.y()) {
      seabed::HeightSample hs;
      scratch.heights.sample(o.x(), o.y(), hs);
      altitude = sb.water_depth_m() - hs.elevation_m - o.z();
    } else {
      altitude = scene.seabed_z(o.x(), o.y()) - o.z();
    }
    if (!bvh.empty() && altitude > 0.0) {
      const double t = bvh.first_hit_m(o, Vec3(0, 0, 1), altitude);
      ++scratch.rays_cast;
      if (t >= 0.0) altitude = t;
    }
  }
  if (!(altitude > 0.05)) {  // out of the water
    echo().finish_lines(options, seed, ping_index, std::numeric_limits<double>::quiet_NaN(),
                        scratch, out);
    return;
  }

  const Mat3 R = pose.R_WV();
  const Vec3 n = R.col(0);
  const double h = std::hypot(n.x(), n.y());
  if (h < 1e-6) {  // pointing straight up or down: no beam plane meets the seabed as a line
    echo().finish_lines(options, seed, ping_index, altitude, scratch, out);
    return;
  }
  const Vec3 ey = R.col(1);
  const Vec3 ez = R.col(2);
  const Vec3 u_stbd(-n.y() / h, n.x() / h, 0.0);
  const Vec3 w = n.cross(u_stbd);
  const double cos_dep = std::cos(sonar_.array.depression_rad);
  const double sin_dep = std::sin(sonar_.array.depression_rad);
  const double dr = sonar_.desc.bin_size_m;
  const double r_hi = std::min(options.range_max_m, sonar_.desc.max_range_m);
  const double r_lo = std::max(0.0, std::floor(options.range_min_m / dr) * dr);

  Line line;
  line.R = &R;
  line.o = o;
  line.n = n;
  line.w = w;
  line.strip = echo().strip();
  line.altitude = altitude;
  line.depth = sb.water_depth_m();
  line.step = plan.step_m;
  // the ray tracer's fan (ray_fan.h) starts here; target rays are laid out on it
  line.r_start = std::max(altitude, r_lo);
  line.r_max = r_hi;
  for (int side = 0; side < 2; ++side) {
    if (!(options.side_mask & (1 << side))) continue;
    line.side = side;
    line.sign = side == 0 ? -1.0 : 1.0;
    line.u = line.sign * u_stbd;
    // sin(off axis) = sin δ cos δ0 − cos δ sin δ0 with sin δ = z_V / ρ, cos δ = ±y_V / ρ, and
    // (y_V, z_V) the in-plane point (s, β) turned into the vehicle frame
    const double uy = line.u.dot(ey), uz = line.u.dot(ez), wy = w.dot(ey), wz = w.dot(ez);
    line.pat_a = uz * cos_dep - line.sign * uy * sin_dep;
    line.pat_b = wz * cos_dep - line.sign * wy * sin_dep;
    for (int j = 0; j < static_cast<int>(echo().along().size()); ++j) {
      line.j = j;
      const double a = echo().along()[static_cast<std::size_t>(j)];
      line.alpha = line.strip ? a : 0.0;
      line.sin_psi = line.strip ? 0.0 : std::sin(a);
      line.inv_cos_psi = line.strip ? 1.0 : 1.0 / std::cos(a);
      line.weight = echo().along_weight()[static_cast<std::size_t>(j)];
      // the march: from nadir (or the shadow margin before the window) to the window's end,
      // clipped to the modelled seabed
      double s_lo = 0.0;
      if (std::isfinite(options.shadow_margin_m)) {
        const double deep = altitude + kSeabedSlack_m;
        const double g = std::sqrt(std::max(0.0, r_lo * r_lo - deep * deep));
        s_lo = std::max(0.0, g - options.shadow_margin_m);
      }
      double s_hi = r_hi / line.inv_cos_psi;  // beyond it every point is out of range
      const Vec2 base = o.head<2>() + line.alpha * n.head<2>() + altitude * w.head<2>();
      clip_axis(base.x(), line.u.x(), sb.extent_min().x(), sb.extent_max().x(), s_lo, s_hi);
      clip_axis(base.y(), line.u.y(), sb.extent_min().y(), sb.extent_max().y(), s_lo, s_hi);
      if (!(s_hi > s_lo)) continue;
      line.s_start = s_lo;
      line.samples = static_cast<int>(std::ceil((s_hi - s_lo) / line.step)) + 1;
      cast_target_rays(scene, line, scratch);
      march(scene, line, options, scratch);
    }
  }
  echo().finish_lines(options, seed, ping_index, altitude, scratch, out);
}

void ProfileRenderer::march(const scene::Scene& scene, const Line& line,
                            const RenderOptions& options, PingScratch& scratch) const {
  seabed::HeightSampler& heights = scratch.heights;
  ProfileLineScratch& ls = scratch.line;
  double* const acc = scratch.accum[line.side].data();
  const EchoModel& em = echo();
  const double bin_m = sonar_.desc.bin_size_m;
  const double inv_dr = 1.0 / bin_m;
  const int bins = sonar_.bins;
  const double* const range_factor = em.range_factor_at_bin().data();
  // only the bins overlapping the range window get echoes (the march starts before it, for the
  // shadows cast into it)
  const int bin_lo =
      std::clamp(static_cast<int>(std::floor(options.range_min_m * inv_dr)), 0, bins);
  const int bin_hi = std::clamp(
      static_cast<int>(std::ceil(std::min(options.range_max_m, sonar_.desc.max_range_m) * inv_dr)),
      0, bins);  // one past the last
  const auto in_window = [&](int bin) { return bin >= bin_lo && bin < bin_hi; };
  const bool targets = !ls.hit_r.empty();
  const bool labels = options.labels;
  const auto bin_of = [inv_dr](double r) { return static_cast<int>(r * inv_dr); };
  const std::size_t n_rays = ls.hit_r.size();
  if (targets) ls.horizon.resize(static_cast<std::size_t>(line.samples));

  // plane geometry, unpacked for the loop
  const double ox = line.o.x(), oy = line.o.y(), oz = line.o.z();
  const double nx = line.n.x(), ny = line.n.y(), nz = line.n.z();
  const double ux = line.u.x(), uy = line.u.y();
  const double wx = line.w.x(), wy = line.w.y(), wz = line.w.z();
  const double inv_wz = 1.0 / wz;
  const bool strip = line.strip;
  const double sin_psi = line.sin_psi;
  const double inv_cos_psi = line.inv_cos_psi;
  const double cos_psi = 1.0 / inv_cos_psi;

  // Echoes are summed per range bin in a register and added to the line when the bin changes,
  // times the range terms (smooth across a bin, so evaluated once at its centre):
  // SL·e^(−2αr)/r³ · W(r). Each piece adds G_v · σ(θ)/sin θ · dφ at its own direction (the
  // vertical pattern can change by tenths of a dB across a bin at short range).
  int open_bin = -1;
  double open_sum = 0.0;
  const auto flush = [&] {
    if (open_bin < 0) return;
    const double width = strip ? line.weight : line.weight * (open_bin + 0.5) * bin_m;
    acc[open_bin] += range_factor[open_bin] * width * open_sum;
    open_sum = 0.0;
  };
  const auto add = [&](int bin, double value) {
    if (bin != open_bin) {
      flush();
      open_bin = bin;
    }
    open_sum += value;
  };

  // Samples are made a block at a time (geometry only: independent of one another), in short
  // passes over the block's arrays, so that many samples are in flight at once: the heights,
  // then the arithmetic (vectorisable), then the table lookups. Then they are visited in order
  // for the horizon and the echoes.
  constexpr int kBlock = 64;
  struct Sample {
    double s, b, rho, inv_rho, alpha;
    double echo;  // G_v · σ(θ)/sin θ at this point (θ from its own surface normal)
    double gx, gy;
    std::uint8_t sediment;
  };
  Sample block[kBlock];
  double px[kBlock], py[kBlock], elev[kBlock], grad_x[kBlock], grad_y[kBlock];
  double sin_graze[kBlock], off_axis[kBlock];
  std::uint8_t sediment[kBlock];
  // Where the plane meets the seabed at s depends on the seabed's depth there (the plane tilts
  // with pitch: the point moves along n by Δβ·|w_xy|) and, for a beam's cone, on the range
  // (α = r·sin ψ). Both are extrapolated linearly from the last two samples of the previous
  // block, and where the plane is tilted or a cone the block is sampled a second time at the
  // point the first pass found (the remaining error is the first's times the seabed slope
  // times sin(pitch): well below a millimetre).
  double dz_last = line.altitude, dz_slope = 0.0;
  double alpha_last = strip ? line.alpha : std::hypot(line.s_start, line.altitude) * sin_psi;
  double alpha_slope = 0.0;
  const bool needs_correction = !strip || std::abs(wx) + std::abs(wy) > 1e-9;
  // sin θ of a point: |d·n| with d = (α n + s u + β w)/r, n = (h_x, h_y, 1)/|.|
  const auto incidence = [&](double s, double b, double inv_rho, double a, double gx, double gy) {
    const double dot =
        (a * nx + s * ux + b * wx) * gx + (a * ny + s * uy + b * wy) * gy + a * nz + b * wz;
    const double inv_gn = 1.0f / std::sqrt(static_cast<float>(gx * gx + gy * gy + 1.0));
    return std::abs(dot) * inv_gn * inv_rho * cos_psi;
  };
  seabed::HeightSample hs;
  const auto read_heights = [&](int n) {
    for (int i = 0; i < n; ++i) {
      heights.sample(px[i], py[i], hs);
      elev[i] = hs.elevation_m;
      grad_x[i] = hs.dh_dx;
      grad_y[i] = hs.dh_dy;
      sediment[i] = hs.sediment;
    }
  };
  // β, ρ, 1/ρ of the block's samples from their heights (ρ and 1/ρ in single precision: 0.1 mm
  // at 50 m is enough to bin, and ratios are exact to 1e-7)
  const auto set_geometry = [&](int n) {
    for (int i = 0; i < n; ++i) {
      Sample& q = block[i];
      const double dz = line.depth - elev[i] - oz;
      q.b = (dz - q.alpha * nz) * inv_wz;
      const float rho = std::sqrt(static_cast<float>(q.s * q.s + q.b * q.b));
      q.rho = rho;
      q.inv_rho = 1.0f / rho;
    }
  };

  // the previous sample P0 (visit order)
  Sample p0{};
  bool hidden0 = false;  // hidden by a target
  // the horizon: the sample with the smallest β/s so far (compared by cross-multiplication)
  double hs_m = 0.0, hb_m = 1.0;  // s, β of that sample; (0, 1) = nothing yet (tan = +inf)
  for (int k0 = 0; k0 < line.samples; k0 += kBlock) {
    const int n = std::min(kBlock, line.samples - k0);
    // where to read: the first guess
    for (int i = 0; i < n; ++i) {
      Sample& q = block[i];
      q.s = line.s_start + (k0 + i) * line.step;
      const double alpha = strip ? alpha_last : alpha_last + (i + 1) * alpha_slope;
      q.alpha = strip ? 0.0 : alpha;  // the offset along n from the transducer (beam cone)
      const double b_guess = (dz_last + (i + 1) * dz_slope - alpha * nz) * inv_wz;
      px[i] = ox + alpha * nx + q.s * ux + b_guess * wx;
      py[i] = oy + alpha * ny + q.s * uy + b_guess * wy;
    }
    // the first guess is a straight line in the block (s, α and the guessed depth all linear
    // in i): walked cell by cell
    if (n > 1) {
      heights.sample_line(px[0], py[0], px[1] - px[0], py[1] - py[0], n, elev, grad_x, grad_y,
                          sediment);
    } else {
      read_heights(n);
    }
    set_geometry(n);
    if (needs_correction) {
      for (int i = 0; i < n; ++i) {
        Sample& q = block[i];
        const double alpha = strip ? line.alpha : q.rho * inv_cos_psi * sin_psi;
        q.alpha = strip ? 0.0 : alpha;
        px[i] = ox + alpha * nx + q.s * ux + q.b * wx;
        py[i] = oy + alpha * ny + q.s * uy + q.b * wy;
      }
      read_heights(n);
      set_geometry(n);
    }
    // The echo terms that depend on the point: the vertical pattern in its direction and
    // σ(θ)/sin θ of its sediment at its incidence, from its own surface normal (the gradient of
    // the bilinear surface there): n = (h_x, h_y, 1)/|.| (z down), sin θ = |d·n|.
    for (int i = 0; i < n; ++i) {
      Sample& q = block[i];
      q.gx = grad_x[i];
      q.gy = grad_y[i];
      q.sediment = sediment[i];
      sin_graze[i] = incidence(q.s, q.b, q.inv_rho, q.alpha, q.gx, q.gy);
      off_axis[i] = (q.s * line.pat_a + q.b * line.pat_b) * q.inv_rho;
    }
    for (int i = 0; i < n; ++i) {
      block[i].echo = em.vertical_pattern_fast(off_axis[i]) *
                      em.seabed_sigma_over_sin(sediment[i], sin_graze[i]);
    }
    {
      const double dz_n = block[n - 1].b * wz + block[n - 1].alpha * nz;
      const double dz_p = n > 1 ? block[n - 2].b * wz + block[n - 2].alpha * nz : dz_n;
      dz_last = dz_n;
      dz_slope = dz_n - dz_p;
      if (!strip) {
        const double a_n = block[n - 1].rho * inv_cos_psi * sin_psi;
        const double a_p = n > 1 ? block[n - 2].rho * inv_cos_psi * sin_psi : a_n;
        alpha_last = a_n;
        alpha_slope = a_n - a_p;
      }
    }
    // visit: horizon, targets, echoes
    for (int i = 0; i < n; ++i) {
      const int k = k0 + i;
      const Sample& p1 = block[i];
      const double s = p1.s, b = p1.b;
      const double r = p1.rho * inv_cos_psi;

      // hidden by a target: inside the tube of a ray that hit one nearer than this sample
      bool hidden1 = false;
      int hidden_ray1 = -1;
      if (targets && s > 0.0) {
        const double tan1 = b / s;
        if (tan1 <= ls.edge_tan[0] && tan1 > ls.edge_tan[n_rays]) {
          // edge_tan decreases: the ray whose tube (edge_tan[i+1], edge_tan[i]] holds tan1
          const auto it = std::upper_bound(ls.edge_tan.begin(), ls.edge_tan.end(),
                                           static_cast<float>(tan1), std::greater<float>());
          const auto ray = static_cast<std::size_t>(
              std::max<std::ptrdiff_t>(0, std::distance(ls.edge_tan.begin(), it) - 1));
          if (ray < n_rays && ls.hit_r[ray] < r) {
            hidden1 = true;
            hidden_ray1 = static_cast<int>(ray);
          }
        }
      }
      // on or above the horizon: β/s ≤ β_m/s_m
      const bool lit1 = b * hs_m <= hb_m * s;
      // labels: seabed the ping sees, or would see but for a target (bin_labels.h)
      if (labels && lit1) count_seabed_sample(scratch.labels, line.side, bin_of(r), hidden1);

      if (k > 0) {
        // the lit part of the segment P0 P1: at or above the horizon ray β = m·s, m = β_m/s_m,
        // where f = β·s_m − m·s·s_m ≤ 0 (f linear along the segment)
        double ta = 0.0, tb = 1.0;
        const double f0 = p0.b * hs_m - hb_m * p0.s;
        const double f1 = b * hs_m - hb_m * s;
        if (f1 > 0.0) {
          tb = 0.0;  // the segment ends behind the horizon (a back slope, or still in shadow)
        } else if (f0 > 0.0) {
          ta = f0 / (f0 - f1);  // it comes out of the shadow here
        }
        // a target's shadow: the half of the segment on the hidden end is dark
        if (hidden0 && hidden1) {
          tb = ta;
        } else if (hidden0) {
          ta = std::max(ta, 0.5);
        } else if (hidden1) {
          tb = std::min(tb, 0.5);
        }
        if (tb > ta) {
          // the angle subtended by the piece t in [t_lo, t_hi] of the segment:
          // |P(t_lo) × P(t_hi)| = (t_hi − t_lo)·|P0 × P1| (P linear in t), over |P(t_lo)|
          // |P(t_hi)|, with 1/ρ linear in t (smooth; second-order error); its echo terms linear in
          // t too
          const double cross = std::abs(p0.s * b - s * p0.b);
          const double d_inv_rho = p1.inv_rho - p0.inv_rho;
          // E(t) = c0 + c1·t + c2·t²: linear between the ends, or, where the echo changes by more
          // than kCurvedEcho along the segment (near nadir, where the vertical pattern is steep;
          // texture), the quadratic through the ends and the middle, integrated exactly over
          // each piece
          double c1 = p1.echo - p0.echo, c2 = 0.0;
          if (std::abs(c1) > kCurvedEcho * (p0.echo + p1.echo)) {
            const double sm = 0.5 * (p0.s + s), bm = 0.5 * (p0.b + b);
            const double inv_rho_m = 0.5 * (p0.inv_rho + p1.inv_rho);
            const double am = 0.5 * (p0.alpha + p1.alpha);
            const double e_mid =
                em.vertical_pattern_fast((sm * line.pat_a + bm * line.pat_b) * inv_rho_m) *
                em.seabed_sigma_over_sin(
                    p0.sediment,
                    incidence(sm, bm, inv_rho_m, am, 0.5 * (p0.gx + p1.gx), 0.5 * (p0.gy + p1.gy)));
            c1 = 4.0 * e_mid - 3.0 * p0.echo - p1.echo;
            c2 = 2.0 * (p0.echo + p1.echo) - 4.0 * e_mid;
          }
          const double c0 = p0.echo;
          const auto deposit = [&](double t_lo, double t_hi, int bin) {
            const double d_phi = cross * (t_hi - t_lo) * (p0.inv_rho + t_lo * d_inv_rho) *
                                 (p0.inv_rho + t_hi * d_inv_rho);
            const double mean_echo = c0 + c1 * 0.5 * (t_lo + t_hi) +
                                     c2 * (t_lo * t_lo + t_lo * t_hi + t_hi * t_hi) / 3.0;
            add(bin, mean_echo * d_phi);
          };
          // ρ along the segment, linear in t (its curvature over a step is below 1e-5 m)
          const double rho_a = p0.rho + ta * (p1.rho - p0.rho);
          const double rho_b = p0.rho + tb * (p1.rho - p0.rho);
          const int bin_a = static_cast<int>(rho_a * inv_cos_psi * inv_dr);
          const int bin_b = static_cast<int>(rho_b * inv_cos_psi * inv_dr);
          if (bin_a == bin_b) {
            if (in_window(bin_a)) deposit(ta, tb, bin_a);
          } else {
            // split at the bin edges crossed, in the order met
            const int dir = bin_b > bin_a ? 1 : -1;
            double t_lo = ta;
            int bin = bin_a;
            for (int guard = 0; bin != bin_b && guard < kMaxPiecesPerSegment; ++guard) {
              const double rho_e = (dir > 0 ? bin + 1 : bin) * bin_m * cos_psi;
              const double t_e = ta + (tb - ta) * (rho_e - rho_a) / (rho_b - rho_a);
              if (in_window(bin)) deposit(t_lo, t_e, bin);
              t_lo = t_e;
              bin += dir;
            }
            if (in_window(bin)) deposit(t_lo, tb, bin);
          }
        }
        // truth: seabed the target hides (lit but for the target)
        if (options.truth && hidden1 && lit1) {
          const int bin = static_cast<int>(r * inv_dr);
          if (bin < bins) {
            const RTCRayHit& rh = scratch.rays[static_cast<std::size_t>(hidden_ray1)];
            TargetTrace& tr = trace_of(scratch.traces, static_cast<int>(rh.hit.geomID), line.side);
            extend_bins(tr.shadow_first, tr.shadow_last, bin);
          }
        }
      }
      if (lit1 && s > 0.0) {
        hs_m = s;
        hb_m = b;
      }
      if (targets) {
        ls.horizon[static_cast<std::size_t>(k)] =
            hs_m > 0.0 ? static_cast<float>(hb_m / hs_m) : std::numeric_limits<float>::infinity();
      }
      p0 = p1;
      hidden0 = hidden1;
    }
  }
  flush();
  scratch.samples += static_cast<std::uint64_t>(line.samples);

  // the targets' echoes, where no nearer seabed rises above their rays
  for (std::size_t i = 0; i < n_rays; ++i) {
    if (!(ls.hit_r[i] < std::numeric_limits<float>::infinity())) continue;
    const double r = ls.hit_r[i];
    const int bin = static_cast<int>(r * inv_dr);
    if (bin >= bins) continue;
    const auto k = static_cast<std::int64_t>(std::floor((ls.ray_s[i] - line.s_start) / line.step));
    if (k >= 0) {
      const double horizon =
          ls.horizon[static_cast<std::size_t>(std::min<std::int64_t>(k, line.samples - 1))];
      if (horizon <= ls.ray_tan[i]) continue;  // the seabed in front hides the hit
    }
    const RTCRayHit& rh = scratch.rays[i];
    const Vec3 d(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
    const Vec3 nrm = Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z).normalized();
    const auto target = static_cast<int>(rh.hit.geomID);
    const EchoModel::TubeEcho e =
        em.target_tube(scratch.meta[i], r, std::fabs(d.dot(nrm)), em.target_scatter(scene, target));
    splat(scratch.accum[line.side], r * inv_dr, e.width_bins, e.intensity);
    if (labels)
      splat(scratch.labels.target_energy[line.side], r * inv_dr, e.width_bins, e.intensity);
    if (options.truth) {
      TargetTrace& tr = trace_of(scratch.traces, target, line.side);
      extend_bins(tr.highlight_first, tr.highlight_last, bin);
      tr.energy += e.intensity;
    }
  }
}

}  // namespace sonarloop::render
