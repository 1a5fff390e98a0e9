#pragma once

// The Rollouts step's "Check what it looks at" panel, from the session's probe/probe.json.

#include <string>

#include "engine/store/session.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// The session's probe with the heat maps of moving `shown_object` (the first object probed when
/// it names none that was); not present when the session has no probe. UserError naming the file
/// for a damaged probe.json.
ui::ProbeView BuildProbeView(const store::Session& session, const std::string& shown_object);

}  // namespace recon::studio
