#pragma once

#include <string>
#include <vector>

namespace recon::studio {

// A training under way is noted in its session's folder from its start to its end: a studio
// closed (or killed) meanwhile leaves the note behind, and the session, opened again, says that
// its training was cut short instead of showing the older models as if nothing had happened.

/// Notes that `methods` start training for `steps` steps each (0: the recipe's) in the session
/// at `session_dir`. UserError naming the file when it cannot be written.
void NoteTrainingStarted(const std::string& session_dir, const std::vector<std::string>& labels,
                         int steps);
/// Removes the note: the training ended (finished, cancelled by the teacher, or failed with an
/// error that was shown).
void NoteTrainingEnded(const std::string& session_dir);
/// What a note left behind says, as the studio shows it ("The training of Baseline and RECON
/// (Play), started 2025-01-31 14:02, was cut short when the studio closed: ..."); "" when
/// there is none.
std::string TrainingCutShort(const std::string& session_dir);

}  // namespace recon::studio
