// The run's checkpoints (Run, run.hpp): at the rotation's checkpoint inclinations, every 'Output/checkpoint
// interval' minutes, and the last converged state of a run that stops, each with what a resumed run needs.
#include "run.hpp"

#include "interruption.hpp"

#include <Teuchos_CommHelpers.hpp>

namespace spatula::app {

RunRecord Run::record_at(const analysis::LoadPoint& p) const
{
  return {initial_internal_, initial_contact_, peak_moment_, peak_force_, p.seconds,
          fields_ ? fields_->state_count() : 0, p.step_control};
}

void Run::write_last_state(const Vector& x, const analysis::LoadPoint& p)
{
  auto record = record_at(p);
  const auto* jump = path_.jump_in_progress();
  if (jump) record.seconds = path_.elapsed_seconds();   // the descent's time so far counts too
  write_checkpoint(checkpoint_file(), last_state_label, *system_, x, p, path_stage_, scene_, record, anchors_.get(),
                   jump);
  note_checkpoint_written();
}

void Run::write_checkpoint_at(double theta_y)
{
  write_checkpoint(checkpoint_file(), checkpoint_label(theta_y), *system_, path_.state(), path_.last(), path_stage_,
                   scene_, record_at(path_.last()), anchors_.get());
  if (root_) out_ << "checkpoint " << checkpoint_label(theta_y) << " written\n";
}

// Every 'Output/checkpoint interval' minutes of wall time, the state to resume from if the run is killed (rank 0's
// clock decides for all).
void Run::checkpoint_if_due(const analysis::LoadPoint& p, const Vector& x)
{
  if (scene_.output.checkpoint_minutes <= 0.0) return;
  const std::chrono::duration<double> interval(60.0 * scene_.output.checkpoint_minutes);
  int due = root_ && clock::now() - last_checkpoint_ > interval;
  Teuchos::broadcast(*comm_, 0, Teuchos::outArg(due));
  if (!due) return;
  write_last_state(x, p);
  last_checkpoint_ = clock::now();
  if (!root_) return;
  out_ << "checkpoint '" << last_state_label << "' written at step " << p.step;
  if (const auto* jump = path_.jump_in_progress())
    out_ << ", with the jump's energy descent at iteration " << jump->iterations;
  out_ << std::endl;
}

}  // namespace spatula::app
