# SPDX-License-Identifier: Apache-2.0
# Silent nonsense made loud (issue 10 §3) and small CLI behaviour (§6); included by CMakeLists.txt.
set(_ds ${PROJECT_SOURCE_DIR}/scenes/validation/double_slit.wscene)
# A sensor in the aperture plate's plane is an error at the sensor's definition.
phasor_cli_test(sensor_in_plate_plane ${_expect} 1 "sensor_in_plate_plane.wscene:6:1: error: sensor 'sensor' lies in the plane of the aperture plate 'plate'"
  --no-file ${_out}/plate_plane.exr -- $<TARGET_FILE:phasor_app> render ${_scenes}/sensor_in_plate_plane.wscene -o ${_out}/plate_plane.exr)
# Black renders: one warning naming the likely cause.
phasor_cli_test(black_wave_from_behind ${_expect} 0 "warning: the image is black: no light reaches the front of sensor 'sensor': light 'wave' arrives from behind"
  -- $<TARGET_FILE:phasor_app> render ${_ds} -D tilt=120deg --spp 1 -o ${_out}/black_tilt.exr)
phasor_cli_test(black_closed_aperture ${_expect} 0 "warning: the image is black: the aperture plate 'plate' has no open area"
  -- $<TARGET_FILE:phasor_app> render ${_ds} -D slit1=false -D slit2=false --spp 1 -o ${_out}/black_closed.exr)
phasor_cli_test(black_infrared_rgb ${_expect} 0 "warning: the image is black: no light emits where the detector responds \\(light 'ir' emits at 1550 nm"
  -- $<TARGET_FILE:phasor_app> render ${_scenes}/infrared_rgb.wscene --spp 1 -o ${_out}/black_ir.exr)
phasor_cli_test(black_camera_inside ${_expect} 0 "warning: the image is black: 100% of the detector's rays start inside shape 'shell'"
  -- $<TARGET_FILE:phasor_app> render ${_scenes}/camera_inside.wscene --spp 1 -o ${_out}/black_inside.exr)
# A lit render is not called black.
add_test(NAME cli.lit_not_black COMMAND sh -c "out=$($<TARGET_FILE:phasor_app> render '${_scenes}/small.wscene' --spp 1 -o '${_out}/lit.exr' 2>&1) && ! echo \"$out\" | grep -q 'image is black'")
set_tests_properties(cli.lit_not_black PROPERTIES LABELS unit)
# A resolution the machine cannot hold is refused with the numbers before anything is allocated
# (PHASOR_MEMORY_LIMIT caps the available memory so the test does not depend on the machine).
phasor_cli_test(memory_refused ${_expect} 1 "huge_sensor.wscene:4:1: error: detector 'sensor': 16384x16384 pixels need about [0-9.]+ GB of memory .* but only 1.07 GB are available. lower its 'resolution'"
  --no-file ${_out}/huge.exr -- env PHASOR_MEMORY_LIMIT=1G $<TARGET_FILE:phasor_app> render ${_scenes}/huge_sensor.wscene -o ${_out}/huge.exr)
# `describe NAME` for a name unique across families; `describe Render` for the Render block; a
# name in several families asks for the family.
phasor_cli_test(describe_by_name ${_expect} 0 "^$" -- $<TARGET_FILE:phasor_app> describe virtual_plane)
phasor_cli_test(describe_render ${_expect} 0 "^$" -- $<TARGET_FILE:phasor_app> describe Render)
phasor_cli_test(describe_ambiguous ${_expect} 1 "'constant' names a plug-in in several families.*phasor describe spectrum constant"
  -- $<TARGET_FILE:phasor_app> describe constant)
phasor_cli_test(describe_name_typo ${_expect} 1 "no plug-in named 'virtual_plan'. did you mean 'virtual_plane'"
  -- $<TARGET_FILE:phasor_app> describe virtual_plan)
# `file = …` is relative to the scene file, Render.output to the working directory.
add_test(NAME cli.output_relative_to_cwd
  COMMAND sh -c "rm -rf '${_out}/cwd' && mkdir -p '${_out}/cwd' && cd '${_out}/cwd' && \
$<TARGET_FILE:phasor_app> render '${_scenes}/output_relative/scene.wscene' --quiet && \
test -f relative_out/scene.exr && test ! -e '${_scenes}/output_relative/relative_out'")
set_tests_properties(cli.output_relative_to_cwd PROPERTIES LABELS unit)
# A one-row sensor's PNG is the profile plot (1000×600), not a 5×1 image.
add_test(NAME cli.one_row_png_is_a_plot
  COMMAND sh -c "rm -f '${_out}/row.png' && $<TARGET_FILE:phasor_app> render \
'${PROJECT_SOURCE_DIR}/scenes/validation/grt_plane_wave_sensor.wscene' -o '${_out}/row.exr' --quiet && \
test \"$(od -An -tu1 -j16 -N8 '${_out}/row.png' | tr -s ' ')\" = ' 0 0 3 232 0 0 2 88'")
set_tests_properties(cli.one_row_png_is_a_plot PROPERTIES LABELS unit)
# A render far beyond the usual is announced before it starts: a 1 pm wavelength makes the
# double slit take minutes per 4096 spp (≈ 200 s on an idle CI machine, 440 s under load); with
# 65536 spp it is ≥ 50 min, far past the 5-minute threshold on any machine. The warning must appear
# within seconds (the test then stops the render).
phasor_cli_test(work_estimate_warns_promptly ${CMAKE_CURRENT_SOURCE_DIR}/work_estimate.sh $<TARGET_FILE:phasor_app>
  ${_ds} ${_out} grt_1pm "lower the spp" -D lambda=1pm --spp 65536)
phasor_cli_test(work_estimate_rs ${CMAKE_CURRENT_SOURCE_DIR}/work_estimate.sh $<TARGET_FILE:phasor_app>
  ${_ds} ${_out} rs_20pm "a longer wavelength" --integrator rs -D lambda=20pm)
# `check` says what `render` would (issue 25 §3): an integrator's refusal comes at load, located.
phasor_cli_test(check_refuses_like_render ${_expect} 1 "small.wscene:8:1: error: integrator 'rs' needs a virtual_plane detector"
  -- $<TARGET_FILE:phasor_app> check ${_scenes}/small.wscene --integrator rs)
phasor_cli_test(render_refuses_at_load ${_expect} 1 "small.wscene:8:1: error: integrator 'rs' needs a virtual_plane detector"
  --no-file ${_out}/small_rs.exr -- $<TARGET_FILE:phasor_app> render ${_scenes}/small.wscene --integrator rs -o ${_out}/small_rs.exr)
# What each integrator can see (issue 26 §2): `ray` cannot reach a plane wave seen through a mirror;
# `check` warns, the black render says why (not "turn the light", which would break grt's render),
# and `compare` shows the warning for ray on its page.
set(_mirror ${PROJECT_SOURCE_DIR}/scenes/validation/screen_behind_mirror.wscene)
phasor_cli_test(check_ray_unreachable ${_expect} 0 "warning: integrator 'ray' cannot reach light 'wave'.*use integrator \"grt\""
  -- $<TARGET_FILE:phasor_app> check ${_mirror} --integrator ray)
phasor_cli_test(black_ray_unreachable ${_expect} 0 "warning: the image is black: integrator 'ray' cannot reach light 'wave'"
  -- $<TARGET_FILE:phasor_app> render ${_mirror} --integrator ray --spp 1 -o ${_out}/mirror_ray.exr)
add_test(NAME cli.compare_shows_unreachable COMMAND sh -c "rm -rf '${_out}/mirror_cmp' && \
$<TARGET_FILE:phasor_app> compare '${_mirror}' --integrators grt,ray --spp 1 -o '${_out}/mirror_cmp' --quiet 2>/dev/null; \
grep -q \"<code>ray</code>: [^<]*integrator .#39.ray.#39. cannot reach light .#39.wave\" '${_out}/mirror_cmp/index.html' && \
grep -q \"^- ray: .*integrator 'ray' cannot reach light 'wave'\" '${_out}/mirror_cmp/results.md' && \
! grep -q \"<code>grt</code>: \" '${_out}/mirror_cmp/index.html'")
set_tests_properties(cli.compare_shows_unreachable PROPERTIES LABELS unit)
# Samplers are plug-ins: an unknown --sampler is an error with a suggestion, before rendering.
phasor_cli_test(unknown_sampler ${_expect} 1 "<command line>.*unknown sampler 'sobl'. did you mean 'sobol'"
  --no-file ${_out}/sobl.exr -- $<TARGET_FILE:phasor_app> render ${_scenes}/small.wscene --sampler sobl -o ${_out}/sobl.exr)
