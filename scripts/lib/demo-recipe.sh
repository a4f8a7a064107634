# shellcheck shell=bash
# The embedded default scenario's recipe, sourced (not run) by scripts/demo.sh (which serves it),
# scripts/bench-viewer.sh (which measures the viewer on it) and scripts/test.sh (whose triangle-
# budget browser test draws its city): one definition, so they all show the same city.
#
# The recipes are word lists of quakeview-prep arguments (split on spaces when used).
QV_DEMO_CITY_RECIPE="synth-city --buildings 100000 --seed 1 --detailed-towers 300"
QV_DEMO_QUAKE_RECIPE="response --synthetic 1 2 3 --epicentre -74.02,40.69,10 --magnitude 6.8"
# Raised when the files a recipe makes change (2: the response's far-view drift series; 3: the
# consequences' "moderate_or_worse" totals; 4: the site's shaking, summary section SITE; 5: files
# stored as Zstandard frames, slim tile summaries, occupants and type mixtures; 6: the situation
# report's casualties by time of day, damage by class and inferred counts; 7: the map under the
# city, streets, a river, parks and neighbourhood names; 8: the city's own districts, its
# neighbourhoods, with consequence totals per district), so a prepared demo from an older version
# is made again.
QV_DEMO_DATA_VERSION=8

# qv_demo_prepare PREP DIR [LOG_PREFIX]: makes the default scenario (city and earthquake) in DIR
# with the quakeview-prep binary PREP, unless DIR already holds it (DIR/.recipe records the
# recipes it was made with). The earthquake takes two to three minutes on 2 cores.
qv_demo_prepare() {
  local prep=$1 data=$2 tag=${3:-[demo]}
  local recipe="$QV_DEMO_CITY_RECIPE; $QV_DEMO_QUAKE_RECIPE; data version $QV_DEMO_DATA_VERSION"
  if [ "$(cat "$data/.recipe" 2>/dev/null)" = "$recipe" ]; then return 0; fi
  echo "$tag preparing the default city: $QV_DEMO_CITY_RECIPE"
  # shellcheck disable=SC2086 # the recipes are word lists
  "$prep" $QV_DEMO_CITY_RECIPE --out "$data" || return 1
  echo "$tag simulating the default earthquake for every building (two to three minutes on 2 cores): $QV_DEMO_QUAKE_RECIPE"
  # shellcheck disable=SC2086
  "$prep" $QV_DEMO_QUAKE_RECIPE --city "$data" || return 1
  echo "$recipe" >"$data/.recipe"
}
