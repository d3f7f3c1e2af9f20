#!/bin/sh
# Runs inside xvfb-run: opens SCENE with `raytrace view`, then carries out
# each STEP in order, waiting after each for what the window prints (never
# for a fixed time), and quits it with the q key. Steps:
#   keys:K1,K2...   press each key (xdotool key names: Left, W, plus, a ...)
#                   and wait for the full frame that it causes
#   press:K1,K2...  press the keys without waiting (h, which draws no frame)
#   frame:K1,K2...  press the keys 30 ms apart and wait for one full frame
#   shot:NAME       screenshot of the window's inside -> DIR/NAME.ppm
#   title:NAME      the window's title -> DIR/NAME.title
#   resize:WxH      resize the window and wait for the frame at that size
#   drag:X,Y,DX,DY  press button 1 at (X, Y) of the window, wait until the
#                   window says it is turning, move by (DX, DY), wait for
#                   the frame, release
#   save:KEYS       press the keys (the last one s) at once, and wait until
#                   the window says it saved
#   quit:SECONDS    let the window trace for SECONDS, press q and time how
#                   long the window takes to exit -> DIR/quit.seconds; the
#                   session ends there
# The window's stderr is left in DIR/log. VIEW_ARGS, if set, are more
# arguments for `raytrace view` (e.g. "--jobs 1"). With FIRST_FRAME=no, the
# steps start once the window is open, not after its first full frame (a
# slow scene's).
# usage: window_session.sh RAYTRACE SCENE DIR STEP...
set -u
raytrace=$1 scene=$2 dir=$3
shift 3
log=$dir/log
: >"$log"
# shellcheck disable=SC2086 # VIEW_ARGS are words
"$raytrace" view ${VIEW_ARGS:-} "$scene" 2>"$log" &
pid=$!

fail() {
  echo "window_session: $*" >&2
  echo "--- window's stderr:" >&2
  cat "$log" >&2
  kill $pid 2>/dev/null
  exit 1
}

count() { grep -c "$1" "$log"; }

# wait_for PATTERN N: until PATTERN occurs at least N times in the log.
wait_for() {
  i=0
  while [ "$(count "$1")" -lt "$2" ]; do
    i=$((i + 1))
    [ $i -le 1500 ] || fail "timed out waiting for '$1' (#$2)"
    kill -0 $pid 2>/dev/null || fail "the window exited while waiting for '$1'"
    sleep 0.02
  done
}

if [ "${FIRST_FRAME:-yes}" = no ]; then wait_for "keys:" 1; else wait_for "drawn" 1; fi
win=$(xdotool search --name "^raytrace: " | head -n 1)
[ -n "$win" ] || fail "no window named raytrace"
# Without a window manager nothing has the focus; xdotool complains then.
xdotool windowfocus --sync "$win" || fail "cannot focus the window"

for step in "$@"; do
  what=${step%%:*} arg=${step#*:}
  case $what in
  keys)
    n=$(count "drawn")
    for k in $(echo "$arg" | tr ',' ' '); do
      xdotool key --window "$win" "$k"
      n=$((n + 1))
      wait_for "drawn" $n
    done
    ;;
  press)
    xdotool key --window "$win" $(echo "$arg" | tr ',' ' ')
    ;;
  frame)
    n=$(count "drawn")
    xdotool key --delay 30 --window "$win" $(echo "$arg" | tr ',' ' ')
    wait_for "drawn" $((n + 1))
    ;;
  shot)
    xwd -silent -nobdrs -id "$win" >"$dir/$arg.xwd" || fail "xwd failed"
    convert "$dir/$arg.xwd" "$dir/$arg.ppm" || fail "convert failed"
    rm -f "$dir/$arg.xwd"
    ;;
  title)
    xdotool getwindowname "$win" >"$dir/$arg.title" || fail "no title"
    ;;
  resize)
    n=$(count "drawn ${arg} ")
    xdotool windowsize "$win" "${arg%x*}" "${arg#*x}"
    wait_for "drawn ${arg} " $((n + 1))
    ;;
  drag)
    set -- $(echo "$arg" | tr ',' ' ')
    t=$(count "turning")
    n=$(count "drawn")
    xdotool mousemove --window "$win" "$1" "$2" mousedown 1
    wait_for "turning" $((t + 1))
    xdotool mousemove --window "$win" $(($1 + $3)) $(($2 + $4))
    wait_for "drawn" $((n + 1))
    xdotool mouseup 1
    ;;
  save)
    n=$(count "saved")
    xdotool key --window "$win" $(echo "$arg" | tr ',' ' ')
    wait_for "saved" $((n + 1))
    ;;
  quit)
    sleep "$arg"
    kill -0 $pid 2>/dev/null || fail "the window exited before q"
    t0=$(date +%s.%N)
    xdotool key --window "$win" q 2>/dev/null
    status=0
    wait $pid || status=$?
    t1=$(date +%s.%N)
    awk "BEGIN { print $t1 - $t0 }" >"$dir/quit.seconds"
    exit $status
    ;;
  *) fail "unknown step $step" ;;
  esac
done

# The window is gone before xdotool sends the key's release: not an error.
xdotool key --window "$win" q 2>/dev/null
status=0
wait $pid || status=$?
exit $status
