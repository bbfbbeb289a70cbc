#!/bin/sh
# Ctrl-C (SIGINT) and SIGTERM during `render --out clip.mp4` leave nothing behind: ffmpeg is
# stopped and its temporary removed (12cc68b left clip.mp4.PID.tmp), and clip.mp4 is not made.
# usage: check_interrupt_render.sh CLOTHSIM SCENE WORKDIR
set -u
clothsim=$1 scene=$2 dir=$3
for sig in INT TERM; do
  rm -rf "$dir"
  mkdir -p "$dir/run"
  # A watcher in the background sends the signal once the video's temporary exists; clothsim
  # runs in the foreground, since a shell starts background jobs with SIGINT ignored.
  (
    tries=0
    until ls "$dir/run" | grep -q '^clip\.mp4\..*\.tmp$'; do
      tries=$((tries + 1))
      [ $tries -gt 600 ] && { echo "no temporary after 60 s"; kill -9 "$(cat "$dir/pid")"; exit 1; }
      sleep 0.1
    done
    sleep 1  # ffmpeg has frames and writes the temporary
    kill -$sig "$(cat "$dir/pid")"
  ) &
  sh -c 'echo $$ >"$1"; shift; exec "$@"' sh "$dir/pid" \
    "$clothsim" render "$scene" --frames 5000 --size 64x48 --samples 1 --out "$dir/run/clip.mp4" >/dev/null 2>&1
  status=$?
  wait
  left=$(ls -A "$dir/run")
  echo "SIG$sig: exit status $status, left: [$left]"
  [ -z "$left" ] || { echo "FAIL: files left behind after SIG$sig"; exit 1; }
  [ $status -gt 128 ] || { echo "FAIL: not ended by the signal"; exit 1; }
done
echo "ok"
