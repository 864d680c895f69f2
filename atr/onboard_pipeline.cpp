#include "atr/onboard_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "units/angles.h"

namespace sonarloop::atr {
namespace {

// The detector's options with the object rules of the model's gates (Model::detector_rules): the
// gates' thresholds were chosen on what a detector with those rules reports.
DetectorOptions detector_options_for(DetectorOptions o, const std::optional<Model>& model) {
  if (model && model->detector_rules) {
    o.min_pings = model->detector_rules->min_pings;
    o.min_along_m = model->detector_rules->min_along_m;
    o.max_along_m = std::max(o.max_along_m, o.min_along_m);
  }
  return o;
}

}  // namespace

OnboardPipeline::OnboardPipeline(std::optional<Model> model, const OnboardOptions& options,
                                 ContactSink sink)
    : options_(options),
      sink_(std::move(sink)),
      receiver_(options.receiver,
                [this](const xtf::XtfFileHeader& h, const xtf::XtfPing& p) { on_ping(h, p); }),
      waterfall_(options.waterfall_pings, options.frame_origin),
      detector_(detector_options_for(options.detector, model)) {
  features_.reserve(gate_feature_count(GateStage::kClassification));
  if (!(options.position_window_m > 0.0)) {
    throw std::invalid_argument("position window must be > 0 m");
  }
  if (!(options.look_radius_m >= 0.0 && std::isfinite(options.look_radius_m))) {
    throw std::invalid_argument("look radius must be >= 0 m (0: no multi-look fusion)");
  }
  if (model) {
    const ChipSpec spec = highlight_chip_spec(model->chip_width, model->chip_height);
    classifier_ = std::make_unique<Classifier>(std::move(*model));
    aligned_ = std::make_unique<AlignedClassifier>(*classifier_, options.search);
    cutter_ = std::make_unique<ChipCutter>(spec, aligned_->margin_rows(), aligned_->margin_cols());
    if (options.look_radius_m > 0.0) looks_ = std::make_unique<LookFusion>(options.look_radius_m);
  }
}

OnboardPipeline::~OnboardPipeline() = default;

void OnboardPipeline::feed(std::span<const std::uint8_t> datagram) {
  receiver_.feed(datagram);
}

void OnboardPipeline::flush() {
  receiver_.flush();
}

void OnboardPipeline::finish() {
  receiver_.flush();
  detector_.finish(waterfall_);
  decided();
}

OnboardStats OnboardPipeline::stats() const {
  OnboardStats s = stats_;
  s.receiver = receiver_.stats();
  s.waterfall_unusable = waterfall_.unusable();
  s.waterfall_resets = waterfall_.resets();
  s.detector = detector_.stats();
  return s;
}

void OnboardPipeline::on_ping(const xtf::XtfFileHeader& header, const xtf::XtfPing& ping) {
  const AddResult added = waterfall_.add(header, ping);
  if (added == AddResult::kUnusable) return;
  if (added == AddResult::kReset) detector_.reset();
  detector_.process(waterfall_);
  decided();
}

void OnboardPipeline::decided() {
  for (const Candidate& c : detector_.candidates()) {
    const bool detected = c.fate == CandidateFate::kReported;
    const bool assessed =
        detected || (options_.classify_candidates && c.fate == CandidateFate::kBelowThreshold);
    if (!detected && !candidate_sink_) continue;
    CandidateReport& r = candidate_;
    r.candidate = c;
    r.p_detection = r.p_classification = std::numeric_limits<double>::quiet_NaN();
    r.classified = nullptr;
    r.reported = false;
    r.contact = assess(c.detection, assessed, &r);
    if (detected && r.passed) report(r.contact);
    r.reported = detected && r.passed;
    if (detected && !r.passed) ++(r.contact.status == "clutter" ? stats_.clutter : stats_.gated);
    if (candidate_sink_) {
      r.gate_features = features_;
      candidate_sink_(r);
    }
  }
}

void OnboardPipeline::locate(const Detection& d, const ChipCentre& centre, double object_height_m,
                             Contact& c) {
  const Waterfall& w = waterfall_;
  // the ping nearest the centre: time, altitude
  std::uint64_t nearest = d.centre_seq;
  double best = std::numeric_limits<double>::infinity();
  double north = 0.0, east = 0.0;
  int n = 0;
  for (std::uint64_t s = w.oldest_seq(); s <= w.newest_seq(); ++s) {
    const PingRecord& r = w.record(s);
    const double off = footprint_along_m(r) - centre.along_m;
    if (std::abs(off) < best) {
      best = std::abs(off);
      nearest = s;
    }
  }
  const PingRecord& rc = w.record(nearest);
  const double a = std::isfinite(rc.altitude_m) ? rc.altitude_m : 0.0;
  const double depth = std::max(0.0, a - 0.5 * object_height_m);
  const double ground = std::sqrt(std::max(0.0, centre.slant_m * centre.slant_m - depth * depth));
  const double side = centre.side == 1 ? 1.0 : -1.0;
  // each nearby ping's view of the object, averaged
  for (std::uint64_t s = w.oldest_seq(); s <= w.newest_seq(); ++s) {
    const PingRecord& r = w.record(s);
    if (std::abs(footprint_along_m(r) - centre.along_m) > options_.position_window_m) continue;
    const double psi = r.heading_deg * kRadPerDeg;
    const double ahead = centre.along_m - r.along_m;  // includes the pitch offset
    north += r.north_m + ahead * std::cos(psi) - side * ground * std::sin(psi);
    east += r.east_m + ahead * std::sin(psi) + side * ground * std::cos(psi);
    ++n;
  }
  if (n == 0) {
    const double psi = rc.heading_deg * kRadPerDeg;
    const double ahead = centre.along_m - rc.along_m;
    north = rc.north_m + ahead * std::cos(psi) - side * ground * std::sin(psi);
    east = rc.east_m + ahead * std::sin(psi) + side * ground * std::cos(psi);
    n = 1;
  }
  north /= n;
  east /= n;
  c.time_utc_ns = rc.time_utc_ns;
  c.ping_number = rc.ping_number;
  c.slant_range_m = centre.slant_m;
  c.ground_range_m = ground;
  if (w.geodetic()) {
    const GeoPoint g = w.to_geodetic(north, east);
    c.latitude_deg = g.latitude_deg;
    c.longitude_deg = g.longitude_deg;
  }
  const Vec2 ne = w.stream_metres(north, east);
  c.north_m = ne.x();
  c.east_m = ne.y();
}

Contact OnboardPipeline::assess(const Detection& d, bool classify, CandidateReport* report) {
  Contact c;
  c.side = d.side;
  c.pings = d.pings;
  c.along_extent_m = d.along_extent_m;
  c.height_m = d.height_m;
  c.shadow_area_m2 = d.shadow_area_m2;
  c.highlight_db = d.highlight_db;
  c.highlight_above_db = d.highlight_above_db;
  c.shadow_below_db = d.shadow_below_db;
  c.highlight_area_m2 = d.highlight_area_m2;
  c.clutter_hits_per_m = d.clutter_hits_per_m;
  ChipCentre centre{d.side, d.along_m, d.slant_m};
  double height = d.height_m;
  report->passed = false;
  detection_features(d, features_);

  const Model* m = classifier_ ? &classifier_->model() : nullptr;
  // the detection gate, before the chip is cut
  if (m && m->detection_gate) {
    report->p_detection = m->detection_gate->probability(features_);
    c.target_probability = report->p_detection;
  }
  const bool detection_passed =
      !(m && m->detection_gate) || report->p_detection >= m->detection_gate->threshold;
  if (!classifier_) {
    c.status = "no_model";
    report->passed = true;  // reported unclassified
  } else if (!classify) {
    c.status = "not_classified";
  } else if (!detection_passed) {
    c.status = "gated";
  } else {
    const auto t0 = std::chrono::steady_clock::now();
    const CutStatus cut = cutter_->cut(waterfall_, centre);
    // a detection that cannot be classified (its chip leaves the swath or the waterfall, or is
    // degenerate) is reported unclassified, unless a classification gate has the last word: it
    // cannot judge it (in a survey the neighbouring line sees it better)
    const bool unjudged_passes = !m->classification_gate;
    if (cut != CutStatus::kOk) {
      c.status = cut_status_name(cut);
      report->passed = unjudged_passes;
    } else {
      const AlignedClassification& a = aligned_->classify(*cutter_);
      stats_.windows += static_cast<std::uint64_t>(a.windows);
      c.windows = a.windows;
      if (a.result.class_index < 0) {
        c.status = chip_status_name(a.check.status);
        report->passed = unjudged_passes;
      } else {
        const Classification& nearest = a.result;
        const bool clutter = m->classes[static_cast<std::size_t>(nearest.class_index)].clutter;
        // the classification gate decides; without one, the nearest class (clutter: not a target)
        classification_features(d, nearest, *m, features_);
        if (m->classification_gate) {
          report->p_classification = m->classification_gate->probability(features_);
          c.target_probability = report->p_classification;
          report->passed = report->p_classification >= m->classification_gate->threshold;
        } else {
          report->passed = !clutter;
        }
        if (clutter && !report->passed) {
          c.status = "clutter";
          c.class_name = m->classes[static_cast<std::size_t>(nearest.class_index)].name;
          c.distance = nearest.distance;
        } else if (!report->passed) {
          c.status = "gated";
        }
        // what is reported: the nearest target class
        classified_ = without_clutter(nearest, *m);
        const Classification& r = classified_;
        if (r.class_index >= 0 && (report->passed || !clutter)) {
          report->classified = &classified_;
          const ClassModel& cls = m->classes[static_cast<std::size_t>(r.class_index)];
          c.class_name = cls.name;
          c.mine_like = r.mine_like;
          c.distance = r.distance;
          if (r.runner_up >= 0)
            c.runner_up = m->classes[static_cast<std::size_t>(r.runner_up)].name;
          c.runner_up_distance = r.runner_up_distance;
          c.mine_distance = r.mine_distance;
          c.non_mine_distance = r.non_mine_distance;
          if (r.subspace_index >= 0) {  // else unknown: [0, 360)
            const Subspace& sub = cls.subspaces[static_cast<std::size_t>(r.subspace_index)];
            c.aspect_min_deg = sub.aspect_min_deg;
            c.aspect_max_deg = sub.aspect_max_deg;
          }
          if (std::isfinite(cls.reject_distance)) {
            c.open_set_score = r.open_set_score;
            c.unknown = r.unknown;
          }
          if (cls.height_m) height = *cls.height_m;  // unknown: the shadow height
        }
        for (std::size_t i = 0; i < m->classes.size(); ++i) {
          const double v = nearest.class_distance[i];
          if (!m->classes[i].clutter) {
            c.scores.emplace_back(m->classes[i].name, v);
          } else if (!c.clutter_distance || v < *c.clutter_distance) {
            c.clutter_distance = v;
          }
        }
        c.shift_rows = a.dr;
        c.shift_cols = a.dc;
        centre = cutter_->shifted(centre, a.dr, a.dc);
      }
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats_.classify_total_s += s;
    stats_.classify_max_s = std::max(stats_.classify_max_s, s);
  }
  locate(d, centre, height, c);
  return c;
}

void OnboardPipeline::report(Contact& c) {
  c.id = ++stats_.contacts;
  const Classification* classified = c.class_name.empty() ? nullptr : &classified_;
  if (classified) {
    ++stats_.classified;
  } else {
    ++stats_.unclassified;
  }
  if (looks_ && classified) {
    const Model& m = classifier_->model();
    const FusedObject& o = looks_->add(c.id, c.north_m, c.east_m, m, *classified);
    c.looks = o.looks;
    c.object = o.id;
    c.fused_class = m.classes[static_cast<std::size_t>(o.class_index)].name;
    c.fused_mine_like = m.classes[static_cast<std::size_t>(o.class_index)].mine_like;
  }
  if (sink_) sink_(c);
}

}  // namespace sonarloop::atr
