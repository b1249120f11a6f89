#!/usr/bin/env bash
# The wine_server CTest fixture of the mingw build: `start` before the Wine console tests,
# `stop` after them.
#
# Why: a wineserver exits a few seconds after its last client, and a test's Wine process that
# connects while it is shutting down loses the connection: the likely cause of CI failing
# headless_errors under ctest -j2 with "wine client error:0: recvmsg: Connection reset by peer"
# (not reproduced on demand). A server started with -p (persistent) does not exit while idle, so
# no console test can meet it exiting; `stop` ends it. The end-to-end tests use copies of the prefix with servers of their own
# (xsession.sh) and do not depend on this one.
# Usage: wineserver.sh start|stop   (WINEPREFIX as for the tests; default ~/.wine)
set -uo pipefail
export WINEDEBUG=${WINEDEBUG:--all}
export WINEDLLOVERRIDES=${WINEDLLOVERRIDES:-"mscoree,mshtml="}
prefix=${WINEPREFIX:-$HOME/.wine}

case "${1:-}" in
start)
  # A fresh prefix is made first (wineboot), as the first Wine program would.
  if [[ ! -f "$prefix/system.reg" ]]; then
    wineboot -i </dev/null >/dev/null 2>&1 || true
    wineserver -w </dev/null >/dev/null 2>&1 || true
  fi
  # The server daemonizes: its standard streams must not be CTest's pipes, or this test would not
  # end before the server does. A server already running (a run interrupted before `stop`, or the
  # user's own Wine programs) is not killed: wait briefly for it to exit, else use it as it is.
  if ! wineserver -p </dev/null >/dev/null 2>&1; then
    timeout 10 wineserver -w </dev/null >/dev/null 2>&1 || true
    if ! wineserver -p </dev/null >/dev/null 2>&1; then
      echo "wineserver.sh: using the wineserver already running for $prefix"
      exit 0
    fi
  fi
  # Wine's services (services.exe, winedevice.exe, ...) start with the first program and then
  # live as long as the server: start them here, with no CTest pipe to inherit.
  wine cmd.exe /c exit 0 </dev/null >/dev/null 2>&1 || true
  echo "wineserver.sh: persistent wineserver started for $prefix"
  ;;
stop)
  wineserver -k </dev/null >/dev/null 2>&1 || true
  echo "wineserver.sh: wineserver for $prefix stopped"
  ;;
*)
  echo "usage: wineserver.sh start|stop" >&2
  exit 2
  ;;
esac
