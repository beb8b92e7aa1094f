#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs a command under a private Xvfb and returns the command's exit status.
#
#   with_xvfb.sh command [args...]
#   SCHLIEREN_XVFB_WM=openbox with_xvfb.sh command...   the same with a window manager (GUI tests
#                                                        that drag windows' contents with xdotool)
#
# Why not `xvfb-run -a`: an X server resets when its last client disconnects, and a connection that
# arrives during the reset is closed unanswered. ParaView opens a display to probe the rendering
# capabilities, closes it and opens the next at once: one time in 5-25 it lost the race and aborted
# with "bad X server connection" (once in CI; back to back, 4-10 % of XOpenDisplay calls failed
# here). -noreset removes the race (0 failures in 3000). Also: xvfb-run takes the first number
# without a /tmp/.X<n>-lock file, although a server that this /tmp does not show (a container beside
# this one) may hold it through its abstract socket. Here the number is random, unnamed by lock files
# and /proc/net/unix, the server must make every socket, and the command starts only once the server
# listens (-displayfd). No access control (-ac): local sockets only, for the command's lifetime.
set -euo pipefail
if [ $# -eq 0 ]; then
  echo "usage: $0 command [args...]" >&2
  exit 2
fi
xvfb=$(command -v Xvfb || true)
if [ -z "$xvfb" ]; then
  echo "with_xvfb.sh: Xvfb is needed (apt-get install xvfb)" >&2
  exit 2
fi
dir=$(mktemp -d "${TMPDIR:-/tmp}/schlieren-xvfb.XXXXXX")
pid=""
child=""
wm=""
cleanup() {
  if [ -n "$child" ]; then
    kill "$child" 2>/dev/null || true
    wait "$child" 2>/dev/null || true
  fi
  if [ -n "$wm" ]; then
    kill "$wm" 2>/dev/null || true
    wait "$wm" 2>/dev/null || true
  fi
  if [ -n "$pid" ]; then
    kill "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  fi
  rm -rf "$dir"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# A number no lock file and no listening socket (file or abstract, this network namespace) names;
# Xvfb is asked for it and dropped if it could not make every socket. -displayfd says when it listens.
start_server() {
  local n=$1
  [ -e "/tmp/.X$n-lock" ] && return 1
  grep -q "/tmp/.X11-unix/X$n\$" /proc/net/unix 2>/dev/null && return 1
  : >"$dir/display"
  "$xvfb" ":$n" -displayfd 3 -screen 0 "${SCHLIEREN_XVFB_SCREEN:-1280x1024x24}" -nolisten tcp -noreset -ac \
    3>"$dir/display" 2>"$dir/log" &
  pid=$!
  for _ in $(seq 300); do
    [ -s "$dir/display" ] && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.05
  done
  if [ -s "$dir/display" ] && ! grep -q "already running\|failed" "$dir/log"; then
    return 0
  fi
  kill "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  pid=""
  return 1
}
started=""
for _ in $(seq 20); do
  if start_server $((1000 + RANDOM % 30000)); then
    started=1
    break
  fi
done
if [ -z "$started" ]; then
  echo "with_xvfb.sh: Xvfb did not start on 20 free-looking displays; its last log:" >&2
  cat "$dir/log" >&2
  exit 2
fi
display=":$(tr -d ' \n' <"$dir/display")"
export DISPLAY="$display"
unset XAUTHORITY
if [ -n "${SCHLIEREN_XVFB_WM:-}" ]; then
  # the window manager, and the command only once it manages the screen (it sets the root
  # window's _NET_SUPPORTING_WM_CHECK)
  "$SCHLIEREN_XVFB_WM" >"$dir/wm.log" 2>&1 &
  wm=$!
  for _ in $(seq 200); do
    xprop -root _NET_SUPPORTING_WM_CHECK 2>/dev/null | grep -q "window id" && break
    kill -0 "$wm" 2>/dev/null || break
    sleep 0.05
  done
  if ! xprop -root _NET_SUPPORTING_WM_CHECK 2>/dev/null | grep -q "window id"; then
    echo "with_xvfb.sh: the window manager $SCHLIEREN_XVFB_WM did not start; its log:" >&2
    cat "$dir/wm.log" >&2
    exit 2
  fi
fi
# in the background so that a TERM (a test's timeout) reaches the command and the server at once
"$@" &
child=$!
status=0
wait "$child" || status=$?
child=""
exit "$status"
