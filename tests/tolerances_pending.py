# ruff: noqa: E501
"""Tolerances in tests/ whose error model is not yet stated next to them (issue 34): only to be removed.

Each entry is (test function, the comparison's text) per file, as ``tests/tolerance_audit.py`` prints them
(``python tests/tolerance_audit.py --pending``).  State the error model in a comment beside the tolerance (one of
``tolerance_audit.STATED_FORMS``; derive it, measure the observed error, set the tolerance about 100 times that)
and remove the entry; ``PENDING_LIMIT`` falls with them and may never rise.  ``tests/test_tolerance_audit.py``
fails on an unstated tolerance not listed here and on an entry no longer in the tests.
"""

PENDING_LIMIT = 129

PENDING: dict[str, list[tuple[str, str]]] = {
    'tests/benchmarks/test_bench_lanes.py': [
        ('test_bench_lanes_batch_2000', 'pytest.approx(ws[2], rel=1e-3)'),
    ],
    'tests/benchmarks/test_bench_linear.py': [
        ('test_bench_eigenvalues_vs_speed', 'np.testing.assert_allclose(np.sort_complex(loop_eig[k]), np.sort_complex(eig[k * LOOP_STRI'),
    ],
    'tests/benchmarks/test_bench_search.py': [
        ('test_bench_critical_impulse_single', 'abs(math.log(b[0].impulse_Ns / a[0].impulse_Ns)) < 0.02'),
    ],
    'tests/benchmarks/test_bench_simulate.py': [
        ('test_bench_adaptive_run', 'pytest.approx(10.0)'),
    ],
    'tests/benchmarks/test_bench_studies.py': [
        ('test_bench_equal_instability_speed', 'pytest.approx(full.speed, rel=1e-6)'),
    ],
    'tests/test_adaptive_stop.py': [
        ('test_the_run_ends_before_the_failure_and_says_why', 'pytest.approx(r.t[-1], abs=5e-5)'),
        ('test_the_samples_before_the_stop_are_those_of_a_run_that_ends_earlier', 'abs(stopped.yaw_rate[i] - short.yaw_rate[-1]) <= bound'),
        ('test_the_samples_before_the_stop_are_those_of_a_run_that_ends_earlier', 'np.max(np.abs(stopped.yaw_rate[:i + 1] - short.yaw_rate)) <= bound'),
    ],
    'tests/test_advise.py': [
        ('test_note_reconciles_a_worse_linear_rate', 'abs(rev.s1 - math.sqrt(ej.i_z / ej.m)) < 0.01'),
    ],
    'tests/test_advise_combinations.py': [
        ('test_the_note_on_a_fix_gives_its_recomputed_gain_or_cost', 'abs(int(pct) - 100 * abs(g)) <= 0.5 + 1e-9'),
    ],
    'tests/test_advise_layout.py': [
        ('test_the_thesis_chair_as_a_layout_has_the_short_forms_trail_and_axle_changes', 'pytest.approx(y, abs=1e-9)'),
        ('test_the_thesis_chair_as_a_layout_has_the_short_forms_trail_and_axle_changes', 'np.testing.assert_allclose(growth_rates(a, [0.75, -0.75]), growth_rates(b, [0.75, -0.75]),'),
        ('test_the_thesis_chair_as_a_layout_has_the_short_forms_linear_measures', 'pytest.approx(s.static_stability_deg.value, rel=1e-9)'),
        ('test_the_thesis_chair_as_a_layout_has_the_short_forms_linear_measures', 'pytest.approx(b, abs=1e-9)'),
        ('test_the_thesis_chair_as_a_layout_has_the_short_forms_linear_measures', 'pytest.approx(s.growth_rate_1_s, rel=1e-9)'),
        ('test_the_shimmy_margin_is_the_smallest_of_the_shimmy_commands_rows', 'pytest.approx(min(margins.values()), abs=1e-12)'),
        ('test_a_suspension_change_keeps_the_weight_and_moves_load_off_the_softened_row', 'pytest.approx(lay.m * lay.g, rel=1e-12)'),
        ('test_reverse_speeds_advise_the_chair_as_its_layout_backwards', 'pytest.approx(float(growth_rates(lay, [-IMPULSE_SPEED])[0]), rel=1e-12)'),
        ('test_reverse_speeds_advise_the_chair_as_its_layout_backwards', 'pytest.approx(band.shimmy_margin_m, rel=1e-12)'),
        ('test_reverse_speeds_advise_the_chair_as_its_layout_backwards', 'pytest.approx(fwd.shimmy_margin_m.value, rel=1e-6)'),
        ('test_the_thesis_chair_as_a_layout_has_the_short_forms_nonlinear_measures', 'pytest.approx(layout_critical_impulses(lay, IMPULSE_SPEED)[0].bound_Ns, rel=1e-12)'),
        ('test_the_thesis_chair_as_a_layout_has_the_short_forms_nonlinear_measures', 'pytest.approx(layout_critical_impulses(lay, IMPULSE_SPEED, __import__( "stability.settings'),
        ('test_a_layouts_drive_and_suspension_levers_offer_the_steps_docs_layouts_lists', 'pytest.approx(sorted(float(x) for x in factors), rel=1e-6)'),
        ('test_the_thesis_chair_as_a_layout_has_the_short_forms_cross_slope_and_driver_measures', 'pytest.approx(short.cross_slope_effort, rel=1e-9)'),
        ('test_the_thesis_chair_as_a_layout_has_the_short_forms_cross_slope_and_driver_measures', 'pytest.approx(short.human_speed_m_s, rel=1e-9)'),
        ('test_the_cross_slope_and_driver_limits_bind_on_the_front_wheel_drive_base', 'pytest.approx(abs(-r * eq.holding_moment_N_m / d), rel=1e-9)'),
        ('test_the_cross_slope_and_driver_limits_bind_on_the_front_wheel_drive_base', 'pytest.approx( abs(layout_cross_slope_effort(moved, a.cross_slope_deg)), rel=1e-12)'),
        ('test_the_thesis_chair_as_a_layout_has_the_short_forms_static_stability_interval', 'pytest.approx(a, rel=1e-9)'),
        ('test_a_mirrored_layout_has_the_same_interval_and_a_higher_cg_lowers_it', 'pytest.approx(a, rel=1e-12)'),
    ],
    'tests/test_app_state.py': [
        ('test_critical_speeds_shown_are_the_command_lines', 'pytest.approx([x.speed for x in want], abs=1e-8)'),
        ('test_trail_chart_crosses_zero_at_the_bands_boundary', 'np.allclose(tw.chart.critical_trail, lower, atol=2e-5)'),
    ],
    'tests/test_assist.py': [
        ('test_discrete_delay_margin_is_the_continuous_one_less_the_sampling_delays', 'pytest.approx(m.continuous.delay_margin_s - 1.5 * T, abs=0.15 * T)'),
        ('test_discrete_delay_margin_is_the_continuous_one_less_the_sampling_delays', 'pytest.approx(g.continuous.delay_margin_s - T, abs=0.2 * T)'),
        ('test_reversing_front_wheel_drive_chair_is_stable', 'pytest.approx(lam, rel=0.03)'),
        ('test_nonlinear_tracking_step_and_slalom', 'pytest.approx(0.8)'),
        ('test_nonlinear_tracking_step_and_slalom', 'np.abs(run.yaw_rate - run.command)[run.t > 1.0].max() < 0.05'),
        ('test_nonlinear_bias_handling', 'pytest.approx(-10.0, abs=0.3)'),
        ('test_nonlinear_bias_handling', 'pytest.approx(-1.0, abs=0.2)'),
        ('test_schedule_from_standstill', 'pytest.approx(-U / chair.trail, rel=0.03)'),
        ('test_schedule_from_standstill', 'pytest.approx(0.8, rel=0.005)'),
        ('test_nonlinear_ramp_saturation_and_noise', 'pytest.approx(0.8, rel=0.01)'),
        ('test_nonlinear_ramp_saturation_and_noise', 'pytest.approx(0.8, rel=0.005)'),
        ('test_driving_figures_have_units_legends_and_titles', 'pytest.approx([-0.1 * 20, -1.0 * 20], rel=0.01)'),
        ('test_driving_figures_have_units_legends_and_titles', 'pytest.approx([-0.1, -1.0], rel=100 * math.exp(-20.0))'),
        ('test_driving_figures_have_units_legends_and_titles', 'pytest.approx(curves.handled[0, -1])'),
        ('test_slope_hold_steady_torque_is_the_statics_holding_moment', 'abs(free.steady_torque_N_m / free.holding_torque_N_m - 1) < driving.HOLD_TOLERANCE'),
        ('test_slope_hold_open_loop_veers_uphill_closed_loop_holds', 'pytest.approx(h.crab_deg, abs=0.2)'),
        ('test_slope_hold_open_loop_veers_uphill_closed_loop_holds', 'pytest.approx(h.crab_deg, abs=0.1)'),
        ('test_slope_hold_figure_and_text', 'pytest.approx(holds[0].holding_torque_N_m)'),
    ],
    'tests/test_assist_export.py': [
        ('test_cli_export_end_to_end', 'np.max(np.abs(c_harness.replay(exe, np.array(case["inputs"])) - np.array(case["outputs"]))'),
        ('test_documented_export_numbers', 'abs(f["gain_db"]) < 1e-12'),
        ('test_documented_export_numbers', 'abs(q15[k] - f[k]) < 5e-4'),
        ('test_documented_export_numbers', 'abs(q31[k] - f[k]) < 1e-8'),
    ],
    'tests/test_assist_faults.py': [
        ('test_bias_step_detection_time_is_the_monitors_closed_form', 'abs(r.detection_time_s - _closed_form_detection(b, T)) <= 2 * T + 1e-12'),
        ('test_documented_fault_table_and_top_speed', 'pytest.approx(turn[5.0])'),
    ],
    'tests/test_assist_layout_checks.py': [
        ('test_the_power_chair_as_a_layout_recovers_as_the_short_form', 'pytest.approx(short.peak_heading_error_deg, rel=0.05)'),
        ('test_the_power_chair_as_a_layout_recovers_as_the_short_form', 'pytest.approx(short.peak_torque_N_m, rel=0.05)'),
        ('test_the_power_chair_as_a_layout_recovers_as_the_short_form', 'pytest.approx(a.predicted_1_s, rel=1e-9)'),
        ('test_the_power_chair_as_a_layout_recovers_as_the_short_form', 'pytest.approx(a.fitted_1_s, rel=1e-6)'),
    ],
    'tests/test_assist_top_speed.py': [
        ('test_delay_margin_is_the_exact_sampled_data_boundary', 'pytest.approx(dm, abs=0.025 * d.sample_time)'),
        ('test_export_warns_beyond_the_safe_top_speed', 'pytest.approx(1e3 * digital.discrete_margins(d).delay_margin_s, abs=0.05)'),
        ('test_export_warns_beyond_the_safe_top_speed', 'pytest.approx(35.0)'),
        ('test_disk_margin_closed_forms', 'pytest.approx(2 / r5, rel=1e-7)'),
        ('test_disk_margin_closed_forms', 'pytest.approx(20 * math.log10((3 + r5) / 2), rel=1e-7)'),
        ('test_disk_margin_closed_forms', 'pytest.approx(math.degrees(2 * math.atan(1 / r5)), rel=1e-7)'),
        ('test_disk_margin_closed_forms', 'pytest.approx(1.0, rel=1e-4)'),
        ('test_disk_margins_of_the_assist_loops', 'pytest.approx(best.fun, rel=1e-5)'),
        ('test_per_wheel_gains_are_the_command_lines_and_make_the_yaw_moment', 'pytest.approx(list(k), rel=5e-4)'),
    ],
    'tests/test_chair.py': [
        ('test_default_chair_is_wchair_block_data', 'pytest.approx(0.66, abs=0.005)'),
    ],
    'tests/test_cli_catalogue.py': [
        ('test_the_smallest_caster_swivel_inertia_answers_the_massless_caster_limit', 'np.testing.assert_allclose(r1, limit, rtol=1e-4)'),
        ('test_small_speed_limit_rates_are_proportional_to_speed_and_below_it_refused', 'abs(mu[0] - mu[1]) < 1e-3 * abs(mu[0])'),
        ('test_slope_answers_a_heavy_chair_under_the_clamp_and_warn_policies', 'pytest.approx(v, abs=1.0)'),
    ],
    'tests/test_compare.py': [
        ('test_numbers_equal_stability_linear', 'np.abs(np.asarray(got) - rates) <= tol'),
        ('test_numbers_equal_stability_linear', 'pytest.approx(locked[0], abs=2e-6)'),
        ('test_locked_critical_speed_matches_eq_5_15_by_hand', 'pytest.approx(expected, rel=1e-5)'),
    ],
    'tests/test_compare_layouts.py': [
        ('test_the_thesis_chairs_as_layouts_get_the_short_forms_growth_rates_and_tip_angles', 'pytest.approx(y, rel=1e-9)'),
        ('test_the_thesis_chair_as_a_layout_gets_the_short_forms_intervals_and_difference_intervals', 'pytest.approx(short.quantity(key).intervals[0], rel=1e-11)'),
        ('test_the_thesis_chair_as_a_layout_gets_the_short_forms_intervals_and_difference_intervals', 'pytest.approx(db.interval, abs=1e-10)'),
        ('test_a_mirrored_layout_is_not_distinguishable_and_a_higher_cg_tips_sooner', 'pytest.approx(q.intervals[0], rel=1e-12)'),
        ('test_a_mirrored_layout_is_not_distinguishable_and_a_higher_cg_tips_sooner', 'pytest.approx((0.0, 0.0), abs=1e-12)'),
    ],
    'tests/test_derivations.py': [
        ('test_exact_conserves_energy_without_forces', 'abs(ke(y1) - ke(y0)) / ke(y0) < 1e-9'),
        ('test_generation_reproduces_committed_files', 'np.allclose(_flat(fa(*args)), _flat(fb(*args)), rtol=1e-10)'),
        ('test_the_door_routes_each_variant_to_its_own_generated_equations', 'np.allclose(accelerations(p, *st, *forces, variant="exact"), accelerations(p, *st, *forces'),
    ],
    'tests/test_driver.py': [
        ('test_best_gain_of_a_one_state_divergence_is_the_double_root', 'pytest.approx(lam - 1.0 / tau, abs=1e-4)'),
        ('test_best_gain_of_a_one_state_divergence_is_the_double_root', 'pytest.approx(math.exp(lam * tau - 1.0) / tau, rel=1e-4)'),
        ('test_pade_is_python_controls_and_the_delay', 'np.max(np.abs(ours - theirs)) < 1e-9'),
        ('test_pade_is_python_controls_and_the_delay', 'np.max(np.abs(ours[low] - np.exp(-1j * w[low] * tau))) < 1e-12'),
        ('test_closed_loop_without_delay_effect_at_zero_gain_is_the_plant', 'np.allclose(ev, expected, atol=1e-8)'),
        ('test_divergence_rule_speed_is_where_lambda_tau_is_one', 'pytest.approx(1.0, abs=100 * SPEED_TOL_M_S * 2.0 * tau)'),
        ('_newton', 'abs(step) < 1e-13 * (1 + abs(s))'),
        ('test_loop_limit_against_the_exact_delay', 'abs(_newton(root, *args) - root) < 1e-7'),
    ],
    'tests/test_driver_tracking.py': [
        ('test_plant_step_is_the_exact_zero_order_hold', 'pytest.approx(x, rel=1e-6)'),
        ('test_operator_gain_table_is_the_double_root_gain', 'np.max(np.abs(ktau / np.exp(theta - 1.0) - 1.0)) < 1e-4'),
        ('test_operator_gain_table_is_the_double_root_gain', 'pytest.approx(math.exp(0.8 - 1.0) / 0.4, rel=1e-3)'),
        ('test_a_delayed_proportional_operator_of_known_delay_is_recovered', 'pytest.approx(tau, rel=0.10)'),
    ],
    'tests/test_impulse_step.py': [
        ('test_the_fixed_step_answer_converges_to_the_adaptive_one', 'abs(fine - ref) / ref < 0.02'),
        ('test_the_fixed_step_answer_converges_to_the_adaptive_one', 'abs(fine - ref) < abs(coarse - ref) / 5'),
    ],
    'tests/test_interface.py': [
        ('test_set_groups_and_units', 'pytest.approx(0.1 * 0.3048 * 0.45359237 * 9.80665, rel=1e-15)'),
    ],
    'tests/test_intervals.py': [
        ('test_batch_rates_equal_one_chair_at_a_time', 'np.abs(np.asarray(row) - ref) <= tol'),
        ('test_batch_locked_critical_speed_equals_zero_width_closed_form', 'np.testing.assert_allclose(crit, closed, rtol=1e-6)'),
        ('test_zero_uncertainty_gives_exactly_the_point_values', 'pytest.approx(r, rel=1e-13)'),
        ('test_monte_carlo_matches_delta_method_on_a_nearly_linear_case', 'abs(hi - dhi) < 0.08 * width'),
        ('test_monte_carlo_matches_delta_method_on_a_nearly_linear_case', 'abs(lo - dlo) < 0.08 * width'),
    ],
    'tests/test_lanes_kernel.py': [
        ('test_lanes_equal_the_scalar_kernel_within_the_rounding_bound', 'pytest.approx(scalar.stats.peak_abs_yaw_rate, abs=_bound(n, scalar.yaw_rate))'),
        ('test_critical_impulse_is_the_same_with_either_kernel', 'pytest.approx(b, rel=0.005)'),
        ('test_critical_impulse_is_the_same_with_either_kernel', 'pytest.approx(thesis, rel=0.01)'),
    ],
    'tests/test_layout.py': [
        ('test_every_preset_as_a_layout_is_the_thesis_model', 'np.max(np.abs(A - A0)) <= 1e-12 * np.max(np.abs(A0))'),
        ('test_reverse_is_the_turned_chair_forward', 'np.allclose(e_rev, e_fwd, rtol=1e-9, atol=1e-9 * np.max(np.abs(e_fwd)))'),
        ('test_a_caster_pair_without_force_or_mass_changes_nothing', 'np.abs(ev[i]) <= 1e-6'),
        ('test_a_caster_pair_without_force_or_mass_changes_nothing', 'np.allclose(np.sort_complex(ev[i][keep]), np.sort_complex(base[i]), rtol=1e-6, atol=1e-6)'),
        ('test_mid_wheel_drive_loads_and_the_compliance_rule', 'abs(n @ x) < 1e-9 * n.sum()'),
        ('test_mid_wheel_drive_loads_and_the_compliance_rule', 'abs(n @ y) < 1e-9 * n.sum()'),
        ('test_the_tipping_command_answers_a_layout', 'pytest.approx(want_high, abs=0)'),
    ],
    'tests/test_layout_figures.py': [
        ('test_the_csv_of_the_thesis_chair_as_a_layout_is_the_short_forms', 'np.abs(a[name] - theirs).max() <= 1e-12 * scale'),
        ('test_the_simulate_command_writes_a_layout_run_mirrored_by_the_push.same', 'np.abs(p - sign * q).max() <= 3e-13 * scale'),
        ('test_the_slope_curves_of_the_thesis_chair_as_a_layout_are_the_short_forms', 'np.testing.assert_allclose(getattr(lay.curve, name), getattr(short.curve, name), rtol=0, a'),
        ('test_the_slope_curves_of_the_thesis_chair_as_a_layout_are_the_short_forms', 'np.testing.assert_allclose(lay.drive_difference, short.drive_difference, rtol=0, atol=2e-1'),
        ('test_the_slope_curves_of_the_thesis_chair_as_a_layout_are_the_short_forms', 'pytest.approx(theirs.heading_change_deg, abs=1e-12)'),
        ('test_the_slope_curves_of_the_thesis_chair_as_a_layout_are_the_short_forms', 'pytest.approx(lay.path.heading_change_deg, abs=1e-12)'),
        ('test_a_slope_to_the_left_draws_the_same_curves', 'np.testing.assert_allclose(getattr(left.curve, name), getattr(right.curve, name), rtol=0, '),
        ('test_a_slope_to_the_left_draws_the_same_curves', 'np.testing.assert_allclose(left.drive_difference, right.drive_difference, rtol=0, atol=2e-'),
        ('test_a_slope_to_the_left_draws_the_same_curves', 'np.testing.assert_allclose(left.path.heading_change_history_deg, right.path.heading_change'),
        ('test_the_trail_chart_of_the_thesis_chair_as_a_layout_is_the_short_forms', 'np.testing.assert_allclose(lay.divergence_rate, short.divergence_rate, rtol=0, atol=2e-11)'),
        ('test_the_trail_chart_of_the_thesis_chair_as_a_layout_is_the_short_forms', 'np.testing.assert_allclose(getattr(lay, name), getattr(short, name), rtol=1e-12, atol=1e-1'),
        ('test_mirror_image_casters_have_the_same_trail_chart', 'np.testing.assert_allclose(getattr(left, name), getattr(right, name), rtol=1e-12, atol=1e-'),
        ('test_mirror_image_casters_have_the_same_trail_chart', 'np.allclose(left.friction_needed, front.friction_needed, rtol=1e-3)'),
        ('test_the_shimmy_command_draws_every_caster_row', 'np.testing.assert_allclose(boundary[0].get_ydata(), np.clip(chart.critical_trail, 0, TRAIL'),
        ('test_set_on_a_layout_file_is_set_on_the_short_form', 'pytest.approx(short[key], abs=2e-12)'),
        ('test_set_on_a_layout_file_is_set_on_the_short_form', 'np.abs(x[name] - y[theirs]).max() <= 1e-12 * np.abs(y[theirs]).max()'),
    ],
}
