#pragma once
// The onboard consumer (docs/design.md, atr/): datagrams of the emulator's sonar stream in, contact
// reports out.
//
//   datagram -> StreamReceiver (decode, reorder, count loss)   atr/stream_receiver.h
//            -> Waterfall (dB re full scale, navigation)       atr/waterfall.h
//            -> Detector (highlight + shadow, one per object)  atr/detector.h
//            -> ChipCutter (the dataset's chip convention)     atr/chip_cutter.h
//            -> AlignedClassifier (eq. 10 at the best shift)   atr/aligned_classifier.h
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
#include <memory>
#include <optional>
#include <span>

#include "atr/aligned_classifier.h"
#include "atr/chip_cutter.h"
#include "atr/contact.h"
#include "atr/detector.h"
#include "atr/look_fusion.h"
#include "atr/stream_receiver.h"
#include "atr/subspace_classifier.h"
#include "atr/waterfall.h"

namespace sonarloop::atr {

struct OnboardOptions {
  ReceiverOptions receiver;
  int waterfall_pings = kDefaultWaterfallPings;
  DetectorOptions detector;
  AlignmentSearch search;
  double position_window_m = 1.5;  // pings averaged for the position (each side of the object)
  // multi-look fusion (atr/look_fusion.h): a classified contact within this distance of an
  // object seen before is fused with it; 0 turns fusion off
  double look_radius_m = kDefaultLookRadius_m;
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
  std::uint64_t classified = 0;    // of which classified
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

  // Without a model, objects are reported unclassified (status "no_model"). Throws
  // std::invalid_argument for bad options or a model whose chips are not highlight chips.
  OnboardPipeline(std::optional<Model> model, const OnboardOptions& options, ContactSink sink);
  ~OnboardPipeline();
  OnboardPipeline(const OnboardPipeline&) = delete;
  OnboardPipeline& operator=(const OnboardPipeline&) = delete;

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
  void report(const Detection& d);
  void locate(const Detection& d, const ChipCentre& centre, double object_height_m, Contact& c);

  OnboardOptions options_;
  ContactSink sink_;
  StreamReceiver receiver_;
  Waterfall waterfall_;
  Detector detector_;
  std::unique_ptr<Classifier> classifier_;
  std::unique_ptr<ChipCutter> cutter_;
  std::unique_ptr<AlignedClassifier> aligned_;
  std::unique_ptr<LookFusion> looks_;  // null when fusion is off
  OnboardStats stats_;
};

}  // namespace sonarloop::atr
