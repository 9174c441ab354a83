# Shared by the restart tests: wait until the checkpoint of step $2 or later
# in directory $1 is complete (checkpoint.info names it), then SIGKILL (no
# clean stop) every process started on $1.prm and wait for the background
# job $3 that started them. Gives up waiting after 120 s. Source this file.
kill_after_checkpoint() { # directory min_step runner_pid
  for i in $(seq 1 1200); do
    if [ -f "$1/checkpoint.info" ] &&
       [ "$(head -1 "$1/checkpoint.info" | cut -d' ' -f1)" -ge "$2" ]; then
      break
    fi
    sleep 0.1
  done
  pkill -KILL -f "softsand $1.prm" || true
  wait "$3" 2> /dev/null || true
}
