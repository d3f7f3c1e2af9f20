#!/bin/sh
# Runs inside xvfb-run: shows SCENE with `raytrace view`, waits until it is
# drawn, takes a screenshot of the window's inside with xwd, quits it with
# the q key, and converts the screenshot to the PPM file OUT.
# usage: window_screenshot.sh RAYTRACE SCENE OUT
set -u
raytrace=$1 scene=$2 out=$3
log=$(mktemp)
"$raytrace" view "$scene" 2>"$log" &
pid=$!
i=0
until grep -q "drawn" "$log"; do
  i=$((i + 1))
  if [ $i -gt 300 ] || ! kill -0 $pid 2>/dev/null; then
    echo "window_screenshot: the window was not drawn:" >&2; cat "$log" >&2; kill $pid 2>/dev/null; exit 1
  fi
  sleep 0.1
done
title="raytrace: $(basename "$scene")"
xwd -nobdrs -silent -name "$title" > "$out.xwd" || { kill $pid; exit 1; }
xdotool search --name "$title" key q
status=0
wait $pid || status=$?
rm -f "$log"
convert "$out.xwd" "$out" && rm -f "$out.xwd"
exit $status
