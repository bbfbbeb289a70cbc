#!/bin/sh
# `render --out FILE.mp4|FILE.gif` starts ffmpeg without a shell: a name with quotes, spaces,
# ';', '$(touch INJECTED)', backquotes and a leading '-' is written as exactly that one file,
# and nothing else appears (no INJECTED, no temporary left). An ffmpeg that dies early (SIGPIPE
# on clothsim's side) or fails is exit 1 with a message, and the old file is left as it was.
# usage: check_render_names.sh CLOTHSIM SCENE OUTDIR
# Run through gpu_test.sh --needs ffmpeg --needs ffprobe (a GL context and both tools).
set -u
bin=$1 scene=$2 base=$3
rm -rf "$base"
mkdir -p "$base"
fail() { echo "FAIL: $*"; exit 1; }
small="--set cloth.num_width_points=7 --set cloth.num_height_points=5 --set cloth.pinned=[[0,0],[6,0]]"
# The hostile part of the name, byte for byte as written here (single quotes keep it literal).
hostile='-it'"'"'s "a" ;$(touch INJECTED);`touch INJECTED` x'
for ext in mp4 gif; do
  dir="$base/$ext"
  mkdir -p "$dir"
  name="$hostile.$ext"
  # From inside the folder, so a command that ran would create INJECTED right here. --fps 30:
  # a GIF plays at most 50 frames/s.
  # shellcheck disable=SC2086 # the --set words split on purpose
  (cd "$dir" && "$bin" render "$scene" $small --frames 2 --size 64x48 --fps 30 --out "$name") \
    >"$base/$ext.log" 2>&1
  code=$?
  cat "$base/$ext.log"
  [ $code -eq 0 ] || fail "render to '$name': exit $code"
  listing=$(ls -A "$dir")
  [ "$listing" = "$name" ] || fail "$dir holds '$listing', expected exactly '$name'"
  [ -e "$base/INJECTED" ] && fail "INJECTED was created in $base"
  [ -e "INJECTED" ] && fail "INJECTED was created in $(pwd)"
  frames=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 \
    "file:$dir/$name")
  [ "$frames" = 2 ] || fail "ffprobe reads '$frames' frames from '$name', expected 2"
  echo "ok: $ext written as exactly '$name' ($frames frames), nothing injected"
done

# A fake ffmpeg first in PATH: one that exits at once without reading (clothsim's writes then
# meet a closed pipe: SIGPIPE, which must not kill it), one that reads everything and fails.
fakes="$base/fakes"
for kind in dies fails; do
  mkdir -p "$fakes/$kind"
  case $kind in
    dies)  printf '#!/bin/sh\nexit 3\n' >"$fakes/$kind/ffmpeg" ;;
    fails) printf '#!/bin/sh\ncat >/dev/null\necho "fake ffmpeg: failing" >&2\nexit 4\n' >"$fakes/$kind/ffmpeg" ;;
  esac
  chmod +x "$fakes/$kind/ffmpeg"
  dir="$base/old_$kind"
  mkdir -p "$dir"
  printf 'an old video' >"$dir/clip.mp4"
  # Enough frames that the pipe's buffer fills and a write meets the dead ffmpeg.
  # shellcheck disable=SC2086
  PATH="$fakes/$kind:$PATH" "$bin" render "$scene" $small --frames 6 --size 256x192 --out "$dir/clip.mp4" \
    >"$base/$kind.log" 2>&1
  code=$?
  cat "$base/$kind.log"
  [ $code -eq 1 ] || fail "a fake ffmpeg that $kind: exit $code, expected 1"
  case $kind in
    dies)  grep -q "clip.mp4: ffmpeg stopped accepting frames.*exit status 3.*clip.mp4 is unchanged" "$base/$kind.log" \
             || fail "no 'stopped accepting frames ... exit status 3 ... unchanged' message" ;;
    fails) grep -q "clip.mp4: ffmpeg failed (exit status 4); .*clip.mp4 is unchanged" "$base/$kind.log" \
             || fail "no 'ffmpeg failed (exit status 4)' message" ;;
  esac
  [ "$(cat "$dir/clip.mp4")" = "an old video" ] || fail "the old clip.mp4 was changed"
  [ "$(ls -A "$dir")" = "clip.mp4" ] || fail "$dir holds $(ls -A "$dir"): a temporary was left"
  echo "ok: an ffmpeg that $kind is exit 1, the old file is untouched, no temporary is left"
done
