#!/usr/bin/env bash
# Runs a ParaView python script headless: render.sh <script.py> <arguments...>
# xvfb-run -a now and then hands pvbatch an X server that is not yet accepting connections ("bad X server
# connection", SIGABRT, most often on a busy machine); such a start is retried, other failures are not.
set -uo pipefail
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for attempt in 1 2 3 4 5; do
  xvfb-run -a -s '-screen 0 1600x1200x24' pvbatch "$@" > "$log" 2>&1
  status=$?
  if [ $status -eq 0 ] || ! grep -q 'bad X server connection' "$log"; then
    grep -v -e '^\s*$' -e 'WARN' "$log"
    exit $status
  fi
  sleep $attempt
done
echo "render.sh: no X server accepted pvbatch after 5 attempts" >&2
exit 1
