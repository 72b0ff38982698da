# strategy.sh -- sourced by the drivers: load commands for a strategy.
# load_lines RULES_DIR STRATEGY prints (load* ...) lines in load order,
# matching rules/src/lib.rs game_files() plus the CLIPS-only stubs.
load_lines() {
  dir=$1
  case "$2" in
    naive) prod="production-naive.clp" ;;
    paper) prod="production.clp select-paper.clp" ;;
    travel) prod="production.clp select-travel.clp" ;;
    *) echo "unknown strategy $2" >&2; return 1 ;;
  esac
  # the stubs stand in for host functions only real CLIPS lacks; our engine has them
  # built in and (like CLIPS) refuses a deffunction that would replace one
  stubs=clips/stubs.clp
  case "${CLIPS:-clips}" in *robotino-agent*) stubs= ;; esac
  for f in $stubs utils.clp worldmodel.clp execution.clp \
           production-common.clp $prod referee.clp game-log.clp sim.clp \
           clips/report.clp; do
    echo "(load* \"$dir/$f\")"
  done
}
