#!/usr/bin/env bash
# Fixture of the browser tests: the bundled scene's report page, made as
# `tools/quickstart.sh run` makes it, the same with its source body (an ease fit), a
# `validate --html` page of its input garment
# (which crosses the dress form, so that page has marked faces to show), and one of two
# layers, the input skirt and the retargeted one (a page with a box per garment), and a
# `validate --animation --html` page of the synthetic sleeve on a bending arm played
# through its clip and the report page of its `retarget --animation` (pages with a frame
# slider; WRITE_BENDING_ARM writes the scene).
#   make_pages.sh GARMENT_RETARGET SCENE_DIR OUT_DIR WRITE_BENDING_ARM
set -euo pipefail
cli="$1" scene="$2" out="$3" write_arm="$4"
rm -rf "$out"
mkdir -p "$out"
"$cli" retarget --garment "$scene/garment.obj" --avatar "$scene/avatar.obj" \
  --no-fit "$scene/no-fit.txt" --out "$out/dress_form" --quiet
# With its source body the fit keeps the skirt's ease, and the page can colour by it.
"$cli" retarget --garment "$scene/garment.obj" --avatar "$scene/avatar.obj" \
  --no-fit "$scene/no-fit.txt" --source-body "$scene/source_body.obj" \
  --out "$out/dress_form_ease" --quiet
status=0
"$cli" validate --garment "$scene/garment.obj" --avatar "$scene/avatar.obj" \
  --html "$out/validate.html" || status=$?
# Exit 1 is validate's verdict "intersections found", expected here.
[ "$status" -eq 1 ]
status=0
"$cli" validate --garment "$scene/garment.obj" --garment "$out/dress_form/garment.obj" \
  --avatar "$scene/avatar.obj" --html "$out/layers.html" || status=$?
[ "$status" -eq 1 ]
"$write_arm" "$out/arm"
status=0
"$cli" validate --garment "$out/arm/sleeve.glb" --avatar "$out/arm/arm.glb" --animation bend \
  --html "$out/animation.html" || status=$?
# Frames of the clip cross: exit 1.
[ "$status" -eq 1 ]
# The sleeve retargeted for the clip (a 45-degree bend, its ease kept): its report.html
# plays the written file, every frame free.
"$write_arm" "$out/arm45" 45
"$cli" retarget --garment "$out/arm45/sleeve.glb" --avatar "$out/arm45/arm.glb" \
  --source-body "$out/arm45/arm.glb" --animation bend --out "$out/arm45/out" --quiet
test -s "$out/dress_form/report.html"
test -s "$out/dress_form_ease/report.html"
test -s "$out/validate.html"
test -s "$out/layers.html"
test -s "$out/animation.html"
test -s "$out/arm45/out/report.html"
