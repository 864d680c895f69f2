#pragma once
// The onboard consumer (docs/design.md, atr/): datagrams of the emulator's sonar stream in, contact
// reports out.
//
//   datagram -> StreamReceiver (decode, reorder, count loss)   atr/stream_receiver.h
//            -> Waterfall (dB re full scale, navigation)       atr/waterfall.h
//            -> Detector (highlight + shadow, one per object)  atr/detector.h
//            -> ChipCutter (the dataset's chip convention)     atr/chip_cutter.h
//            -> detection gate (the detector's features)        atr/contact_gate.h
//            -> ChipCutter ... AlignedClassifier (below)
//            -> classification gate (and the distances)        atr/contact_gate.h
//               (with a classification gate, a detection whose chip cannot be cut or
//               classified is not reported: the gate cannot judge it)
//               (without gates: an object identified as a clutter class, the detector's own
//               false alarms learnt from training surveys, is not reported)
//            -> LookFusion (fuse a re-seen object's looks)      atr/look_fusion.h
//            -> Contact (JSON line)                            atr/contact.h
//
// Object position. The classifier's best window refines the object's centre (along track and
// slant range). Its ground range is g = sqrt(r^2 - d^2) with d the depth of the centre below the
// sonar: the ping's altitude less half the identified class's height (stored in the model,
// ClassModel::height_m; the detector's shadow height when the class's height is unknown or
// without a class). Each ping k within position_window_m of the
// centre puts the object at p_k + (s - s_k) u_k ± g v_k (p_k its navigation position, s_k its
// dead-reckoned along-track position, s the object's footprint along-track position, u_k and
// v_k the unit vectors along and to starboard of its heading, + starboard, - port); the report
// gives their mean, which averages out the navigation's white position noise.
//
// Threading: single-threaded; feed() from one thread (atr/packet_queue.h decouples a socket or
// the emulator from it). The same datagrams give the same contacts (no wall clock in them);
// timings go to the statistics only.
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>

#include "atr/aligned_classifier.h"
#include "atr/chip_cutter.h"
#include "atr/contact.h"
#include "atr/contact_gate.h"
#include "atr/detector.h"
#include "atr/look_fusion.h"
#include "atr/stream_receiver.h"
#include "atr/subspace_classifier.h"
#include "atr/waterfall.h"

namespace sonarloop::atr {

// One candidate of the detector (atr/detector.h, Candidate) as the pipeline saw it: located like a
// contact, classified when it was reported (or, with classify_candidates, whenever it survived
// the suppression), for scoring the detector and the classifier over their thresholds.
struct CandidateReport {
  Candidate candidate;
  Contact contact;        // id 0 unless reported; class empty unless classified
  bool passed = false;    // the gates passed (or none: not identified as a clutter class)
  bool reported = false;  // a contact went out (the detector reported it and it passed)
  // the contact gates' target probabilities (atr/contact_gate.h), NaN where not evaluated
  double p_detection = std::numeric_limits<double>::quiet_NaN();
  double p_classification = std::numeric_limits<double>::quiet_NaN();
  // the gate features: the classification stage's when the chip was classified, else the
  // detection stage's (for training gates on surveys)
  std::vector<double> gate_features;
  const Classification* classified = nullptr;  // valid in the sink's call only
};

struct OnboardOptions {
  ReceiverOptions receiver;
  int waterfall_pings = kDefaultWaterfallPings;
  DetectorOptions detector;
  AlignmentSearch search;
  double position_window_m = 1.5;  // pings averaged for the position (each side of the object)
  // multi-look fusion (atr/look_fusion.h): a classified contact within this distance of an
  // object seen before is fused with it; 0 turns fusion off
  double look_radius_m = kDefaultLookRadius_m;
  // classify the candidates below the detector's threshold too (for the candidate sink only:
  // offline scoring; costs a classification per candidate)
  bool classify_candidates = false;
  // origin of the contacts' north_m / east_m for latitude/longitude streams (a scenario's
  // origin, so that contacts agree with its scene.json and truth.json); none: the first ping
  std::optional<GeoPoint> frame_origin;
};

struct OnboardStats {
  ReceiverStats receiver;
  std::uint64_t waterfall_unusable = 0;  // pings that were not a two-channel sidescan
  std::uint64_t waterfall_resets = 0;    // geometry changes
  DetectorStats detector;
  std::uint64_t contacts = 0;      // reported
  std::uint64_t clutter = 0;       // detections identified as a clutter class, not reported
  std::uint64_t gated = 0;         // detections a contact gate kept out
  std::uint64_t classified = 0;    // of the contacts: classified
  std::uint64_t unclassified = 0;  // chip could not be cut, or was rejected
  std::uint64_t windows = 0;       // chips classified (all alignment windows)
  double classify_total_s = 0.0;   // cutting + classifying, all contacts
  double classify_max_s = 0.0;     // the slowest contact
  double seconds_per_chip() const {
    return windows ? classify_total_s / static_cast<double>(windows) : 0.0;
  }
  double seconds_per_contact() const {
    return classified ? classify_total_s / static_cast<double>(classified) : 0.0;
  }
};

class OnboardPipeline {
 public:
  using ContactSink = std::function<void(const Contact&)>;
  using CandidateSink = std::function<void(const CandidateReport&)>;

  // Without a model, objects are reported unclassified (status "no_model"). A model that records
  // the detector rules its gates were trained behind (Model::detector_rules) sets the detector's
  // min_pings and min_along_m over options.detector's. Throws
  // std::invalid_argument for bad options or a model whose chips are not highlight chips.
  OnboardPipeline(std::optional<Model> model, const OnboardOptions& options, ContactSink sink);
  ~OnboardPipeline();
  OnboardPipeline(const OnboardPipeline&) = delete;
  OnboardPipeline& operator=(const OnboardPipeline&) = delete;

  // Every candidate of the detector, as its fate is decided (reported ones after their contact
  // went to the contact sink). Default: none.
  void set_candidate_sink(CandidateSink sink) { candidate_sink_ = std::move(sink); }

  void feed(std::span<const std::uint8_t> datagram);
  // The stream went quiet: hand over the pings waiting in the reorder buffer.
  void flush();
  // End of the stream: flush, then decide and report every object still open.
  void finish();

  OnboardStats stats() const;
  const Waterfall& waterfall() const { return waterfall_; }
  bool has_model() const { return classifier_ != nullptr; }

 private:
  void on_ping(const xtf::XtfFileHeader& header, const xtf::XtfPing& ping);
  // A contact for `d` (no id, no look fusion): through the gates and classified when `classify`
  // and a model is loaded, located; whether it passed and the gates' figures into *report.
  Contact assess(const Detection& d, bool classify, CandidateReport* report);
  // Reports the contact of the last assess(): id, look fusion, the contact sink.
  void report(Contact& c);
  void decided();  // the detector's candidates of the last call: reported ones, the sink
  void locate(const Detection& d, const ChipCentre& centre, double object_height_m, Contact& c);

  OnboardOptions options_;
  ContactSink sink_;
  CandidateSink candidate_sink_;
  StreamReceiver receiver_;
  Waterfall waterfall_;
  Detector detector_;
  std::unique_ptr<Classifier> classifier_;
  std::unique_ptr<ChipCutter> cutter_;
  std::unique_ptr<AlignedClassifier> aligned_;
  std::unique_ptr<LookFusion> looks_;  // null when fusion is off
  Classification classified_;          // the last assess()'s, its clutter classes left out
  std::vector<double> features_;       // the last assess()'s gate features
  CandidateReport candidate_;          // the one being decided (reused: no allocation per ping)
  OnboardStats stats_;
};

}  // namespace sonarloop::atr
