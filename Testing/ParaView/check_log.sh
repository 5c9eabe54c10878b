#!/usr/bin/env bash
# Fails (exit 1) when ParaView's log LOG has an error or warning line, printing them and
# WHAT logged them: check_log.sh LOG WHAT. The same lines ParaView.PluginLog's
# FAIL_REGULAR_EXPRESSION (CMakeLists.txt) catches.
log=$1 what=$2
if grep -En 'ERR\||WARN\||ERROR|[Ww]arning|Could not create' "$log"; then
  echo "FAIL: $what logged the errors or warnings above"
  exit 1
fi
