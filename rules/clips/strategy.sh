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
  for f in clips/stubs.clp utils.clp worldmodel.clp execution.clp \
           production-common.clp $prod referee.clp game-log.clp sim.clp snapshot.clp \
           clips/report.clp; do
    echo "(load* \"$dir/$f\")"
  done
}
