#pragma once

// What a method's features encode, read out on a session's recorded frames: for a real cell's
// session, where nothing can be rendered again, the beacons' own readings are the truth a
// linear read-out from phi is scored against, on whole recorded episodes it was not fitted on.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/beacon_spec.h"
#include "engine/core/dataset.h"
#include "engine/probe/distractor_probe.h"
#include "engine/probe/linear_readout.h"

namespace recon::probe {

/// Frames of recorded episodes with what the beacons read at each.
struct RecordedFrames {
  ProbeSubject::Rows xs, ys;
  std::vector<int> episodes;  ///< the episode each frame is of (numbered from 0)
  int episode_count = 0;      ///< episodes the frames come from
  /// Object -> its beacon's reading per frame.
  std::map<std::string, std::vector<std::vector<double>>> readings;
};

/// At most `max_frames` frames of `data` (its demonstrations, then its play chunks; evenly
/// strided over all of them), each beacon's reading filed under the object it marks
/// (`objects[i]` for beacons[i]). UserError when `objects` and `beacons` differ in count or
/// the readings are not the beacons' size.
RecordedFrames SampleRecordedFrames(const Dataset& data, const std::vector<BeaconSpec>& beacons,
                                    const std::vector<std::string>& objects, int max_frames);

/// Per object, the read-out of its beacon's reading from `subject`'s features, cross-validated
/// over the recorded episodes (each quarter of them held out whole in turn, the ridge chosen
/// within the others: CrossValidatedReadout); none for fewer than 8 episodes, or when the object
/// stood in one place (its episodes' mean readings within 1 cm) over all of them.
std::map<std::string, std::optional<ReadoutScore>> ReadOutRecorded(const ProbeSubject& subject,
                                                                   const RecordedFrames& frames);

}  // namespace recon::probe
