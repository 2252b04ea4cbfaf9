#!/usr/bin/env bash
# The viewer draws a scene: run ode-bpp-viewer headless under Xvfb for a few frames of the box
# stack, take its screenshot, convert it to PNG (kept in $ODE_BPP_BINARY_DIR/artifacts/) and
# check that it is a full frame, not one flat colour, and that the scene's bodies are in it.
# The bodies are drawn in saturated colours over a grey ground, so the lower three quarters of
# the frame (below the sky) must hold a share of saturated pixels; without them it holds none.
# The frame describes itself: scene, solver, time and solve time are written white on a dark
# panel in its top left corner, over the bright sky, so that corner must be dark on average and
# hold a share of white pixels (the sky alone: mean lightness ~0.85, half of it above 0.85).
set -euo pipefail

: "${ODE_BPP_BINARY_DIR:?set by ctest (tests/CMakeLists.txt)}"
viewer="$ODE_BPP_BINARY_DIR/demos/viewer/ode-bpp-viewer"
artifacts="$ODE_BPP_BINARY_DIR/artifacts"
scene=boxstack
frames=30
width=800 height=600
min_colours=256          # a flat or near-flat frame has a handful
min_body_share=0.05      # saturated pixels below the horizon; the box stack fills ~20 %
panel=280x50+10+10       # the text panel's corner, inside it for any font (WxH+X+Y pixels)
max_panel_lightness=0.5  # mean lightness there; the panel: ~0.35, the sky: ~0.85
min_text_share=0.02      # white pixels (lightness > 0.85) in that corner; text: ~6 %

fail() { echo "viewer_screenshot: FAIL: $*" >&2; exit 1; }

[[ -x "$viewer" ]] || fail "no viewer at $viewer (is ODE_BPP_BUILD_DEMOS on and drawstuff installed?)"
for tool in xvfb-run convert identify; do
    command -v "$tool" >/dev/null || fail "$tool is not installed"
done

mkdir -p "$artifacts"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
ppm="$work/$scene.ppm"
png="$artifacts/viewer_$scene.png"
rm -f "$png"

timeout 300 xvfb-run -a -s "-screen 0 ${width}x${height}x24" \
    "$viewer" "$scene" --solver dantzig --frames "$frames" --screenshot "$ppm" >"$work/viewer.log" 2>&1 \
    || { cat "$work/viewer.log" >&2; fail "the viewer exited with an error"; }
[[ -s "$ppm" ]] || { cat "$work/viewer.log" >&2; fail "no screenshot written"; }

convert "$ppm" "$png" || fail "convert could not turn $ppm into PNG"
[[ -s "$png" ]] || fail "no PNG at $png"

size=$(identify -format '%wx%h' "$png")
[[ "$size" == "${width}x${height}" ]] || fail "screenshot is $size, expected ${width}x${height}"

colours=$(identify -format '%k' "$png")
(( colours > min_colours )) || fail "only $colours distinct colours (needs > $min_colours): a flat frame"

body_share=$(convert "$png" -gravity south -crop 100%x75%+0+0 +repage -colorspace HSL \
    -channel G -separate +channel -threshold 25% -format '%[fx:mean]' info:)
awk -v s="$body_share" -v m="$min_body_share" 'BEGIN { exit !(s > m) }' \
    || fail "saturated share below the horizon is $body_share (needs > $min_body_share): no bodies drawn"

panel_lightness=$(convert "$png" -crop "$panel" +repage -colorspace Gray -format '%[fx:mean]' info:)
text_share=$(convert "$png" -crop "$panel" +repage -colorspace Gray -threshold 85% -format '%[fx:mean]' info:)
awk -v l="$panel_lightness" -v m="$max_panel_lightness" 'BEGIN { exit !(l < m) }' \
    || fail "the top left corner has mean lightness $panel_lightness (needs < $max_panel_lightness): no text panel"
awk -v s="$text_share" -v m="$min_text_share" 'BEGIN { exit !(s > m) }' \
    || fail "the text panel holds $text_share white pixels (needs > $min_text_share): no text"
grep -q "no X font" "$work/viewer.log" && fail "the viewer found no X font for its text"

echo "viewer_screenshot: OK: $png ($size, $colours colours, body share $body_share, panel lightness $panel_lightness, text $text_share)"
