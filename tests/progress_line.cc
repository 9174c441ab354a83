// The progress line's estimate of the wall time left counts the rate of
// this process's own steps: a run restarted from a checkpoint halfway to
// its end time must not divide its wall time by the steps it resumed.

#include <softsand/drivers/scene_setup.h>

#include "tests.h"

int
main()
{
  initlog();
  using softsand::drivers::progress_of;
  // 10 s of loop wall time for 0.1 s of simulated time, 0.4 s to go.
  deallog << "fresh run at 0.1 of 0.5 s after 10 s: "
          << progress_of(0.1, 0, 0.5, 10) << std::endl;
  // Resumed at 0.3 s: 10 s for 0.1 s, 0.1 s to go.
  deallog << "resumed at 0.3 s, at 0.4 of 0.5 s after 10 s: "
          << progress_of(0.4, 0.3, 0.5, 10) << std::endl;
  deallog << "resumed at 0.3 s, no step yet: " << progress_of(0.3, 0.3, 0.5, 0)
          << std::endl;
  deallog << "no end time: " << progress_of(0.3, 0, 0, 5) << std::endl;
}
