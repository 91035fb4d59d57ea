# ruff: noqa: E501
"""Tolerances in tests/ whose error model is not yet stated next to them (issue 34): only to be removed.

Each entry is (test function, the comparison's text) per file, as ``tests/tolerance_audit.py`` prints them
(``python tests/tolerance_audit.py --pending``).  State the error model in a comment beside the tolerance (one of
``tolerance_audit.STATED_FORMS``; derive it, measure the observed error, set the tolerance about 100 times that)
and remove the entry; ``PENDING_LIMIT`` falls with them and may never rise.  ``tests/test_tolerance_audit.py``
fails on an unstated tolerance not listed here and on an entry no longer in the tests.
"""

PENDING_LIMIT = 117

PENDING: dict[str, list[tuple[str, str]]] = {
    'tests/test_layout_impulse.py': [
        ('test_reverse_casters_start_trailing_for_the_reverse', 'math.isclose(push_impulse(1.0, 0.1), 0.101)'),
        ('test_a_slow_divergence_is_not_reported_as_robustness', 'math.isclose(slow.growth_rate, growth, rel_tol=1e-9)'),
        ('test_a_slow_divergence_is_not_reported_as_robustness', 'pytest.approx(10.0, abs=2e-3)'),
    ],
    'tests/test_layout_reverse_casters.py': [
        ('test_only_casters_across_the_path_turn_a_chair_backing_up_undisturbed', 'abs(err[0.0]) < 1e-9'),
        ('test_only_casters_across_the_path_turn_a_chair_backing_up_undisturbed', 'abs(err[180.0]) < 1e-9'),
    ],
    'tests/test_layout_simulate.py': [
        ('test_the_thesis_chair_as_a_layout_is_the_thesis_engine', 'np.abs(ours.heading_rad - np.asarray(theirs.heading)).max() <= 1e-11'),
        ('test_the_thesis_chair_as_a_layout_is_the_thesis_engine', 'np.abs(ours.caster_angle_rad[0] - np.asarray(theirs.eta)).max() <= 1e-10'),
        ('test_the_thesis_chair_as_a_layout_is_the_thesis_engine', 'np.abs(ours.caster_angle_rad[1] - np.asarray(theirs.beta)).max() <= 1e-10'),
        ('test_a_caster_off_the_ground_without_mass_changes_nothing', 'np.abs(a.heading_rad - b.heading_rad).max() <= 1e-7 * peak'),
        ('test_the_linear_growth_rate_is_recovered_from_the_nonlinear_run', 'abs(fit - lam) <= 0.01 * abs(lam)'),
    ],
    'tests/test_layout_slope.py': [
        ('test_the_holding_moment_is_the_statics_closed_form', 'pytest.approx(_closed_form(layout, 2.0, speed < 0), rel=2e-3)'),
        ('test_the_holding_moment_is_the_statics_closed_form', 'abs(a - back) < 1.0'),
        ('test_a_slope_to_the_left_needs_the_opposite_holding_moment', 'pytest.approx(-(left.caster_angles_deg[j] - back), abs=1e-8)'),
    ],
    'tests/test_layout_slope_run.py': [
        ('test_the_thesis_chair_as_a_layout_is_the_thesis_engine_on_a_slope', 'np.abs(mine[:n] - np.asarray(ref)[:n]).max() <= 1e-9'),
        ('test_on_a_grade_alone_the_speed_changes_at_g_sin_theta', 'np.abs(r.u_m_s - expected).max() <= 1e-11'),
        ('test_on_a_grade_alone_the_speed_changes_at_g_sin_theta', 'np.abs(r.heading_rad).max() <= 1e-12'),
        ('test_on_a_grade_alone_the_speed_changes_at_g_sin_theta', 'np.abs(r.caster_angle_rad - np.radians(angles)[:, None]).max() <= 1e-12'),
    ],
    'tests/test_layout_toe.py': [
        ('test_the_layout_linear_model_with_toe_is_the_short_form_simulator_linearised', 'abs(forward_acceleration(c, speed, drive=(drive, drive))) <= 1e-9'),
        ('test_the_layout_linear_model_with_toe_is_the_short_form_simulator_linearised', 'np.abs(ours - theirs).max() <= 3e-6'),
        ('test_toe_as_a_layout_runs_as_the_short_form_with_toe', 'np.abs(mine - np.asarray(ref)).max() <= 1e-9'),
        ('test_symmetric_toe_keeps_straight_running_straight', 'np.abs(r.heading_rad).max() <= 1e-12'),
        ('test_toe_in_reverse_is_the_turned_chair_with_toe_forward', 'np.allclose(rev, fwd, rtol=1e-9, atol=1e-9 * np.abs(fwd).max())'),
    ],
    'tests/test_linear.py': [
        ('test_eq_8_5_with_the_tire_fits', 'pytest.approx(12, rel=0.15)'),
        ('test_state_space_object', 'np.testing.assert_allclose(sys.B[1, 0], 1 / c.i_z, rtol=0.05)'),
    ],
    'tests/test_paths_agree.py': [
        ('test_slope_command_and_report_name_the_same_side', 'pytest.approx(regression.value("ej_handrim_force_difference_6deg_N"), abs=0.01)'),
        ('test_slope_command_and_report_name_the_same_side', 'abs(diff - (-m_cf / c.d1 * hr.wheel_radius / hr.handrim_radius)) <= pins'),
    ],
    'tests/test_report.py': [
        ('test_tire_page_stiffness_equals_critical_speed', 'pytest.approx(printed["main"], rel=1e-12)'),
        ('test_tire_page_stiffness_equals_critical_speed', 'pytest.approx(printed["caster"], rel=1e-12)'),
        ('test_tire_page_stiffness_equals_critical_speed', 'pytest.approx( np.interp(main.load, curves.fz, curves.stiffness[curves.names.index(c.main_'),
        ('test_findings_numbers_match_the_analysis', 'pytest.approx(d.thesis.reference_time, abs=1e-12)'),
        ('test_findings_numbers_match_the_analysis', 'pytest.approx(0.05)'),
        ('test_findings_numbers_match_the_analysis', 'pytest.approx(0.15)'),
        ('test_conclusions_under_the_thesis_conditions', 'pytest.approx(0.60)'),
        ('test_conclusions_under_the_thesis_conditions', 'pytest.approx(0.62)'),
        ('test_reference_chair_rates_itself_at_the_reference_speed', 'pytest.approx(0.75, abs=0.05)'),
        ('test_summary_numbers_come_from_the_data', 'pytest.approx([f * THESIS_PUSH.force for f in study.PUSH_FACTORS])'),
        ('test_slope_numbers_equal_the_analysis', 'pytest.approx(statics, rel=0.002)'),
        ('test_shimmy_numbers_equal_the_analysis', 'pytest.approx(rigid.relaxation_length, rel=1e-3)'),
        ('test_zero_spread_gives_exactly_the_point_values', 'pytest.approx(point, rel=1e-12)'),
        ('test_cg_ratio_span_keeps_static_loads_positive', 'pytest.approx(0.02, abs=1e-9)'),
        ('test_cg_ratio_span_keeps_static_loads_positive', 'pytest.approx(p.span(fc)[1])'),
        ('test_cg_ratio_span_keeps_static_loads_positive', 'pytest.approx(0.02, abs=1e-9)'),
        ('test_trail_window_and_tip_limits', 'pytest.approx(LOANE_KIRBY_REAR_DEG, abs=1e-3)'),
    ],
    'tests/test_report_clinician.py': [
        ('test_bump_times_are_the_simulators', 'pytest.approx(t_level, abs=2e-3)'),
    ],
    'tests/test_report_layout_options.py': [
        ('test_the_thesis_chairs_sheet_as_a_layout_is_the_short_forms', 'pytest.approx(m.time_to_level, rel=5e-4)'),
        ('test_the_thesis_chairs_sheet_as_a_layout_is_the_short_forms', 'pytest.approx(x, rel=1e-9)'),
        ('test_a_reverse_bump_run_is_valid_while_it_backs', 'pytest.approx(10.0, abs=0.01)'),
        ('test_a_reverse_bump_run_is_valid_while_it_backs', 'pytest.approx(7.5, rel=0.05)'),
    ],
    'tests/test_report_wheel_layouts.py': [
        ('test_the_thesis_chair_as_a_layout_reports_the_short_forms_growth_rates_and_tip_angles', 'pytest.approx(float(y), rel=1e-9)'),
        ('test_a_frame_turned_round_has_its_shimmy_rows_swapped_between_directions', 'pytest.approx(b[other]["interval_m"][1], rel=1e-12)'),
        ('test_the_driver_section_is_the_short_forms_rule_for_the_thesis_chair_and_mirrors_for_a_turned_frame', 'pytest.approx(h.rule_speed_m_s, rel=1e-9)'),
        ('test_the_driver_section_is_the_short_forms_rule_for_the_thesis_chair_and_mirrors_for_a_turned_frame', 'pytest.approx(b["forward"]["rule_speed_m_s"], rel=1e-9)'),
        ('test_the_driver_section_is_the_short_forms_rule_for_the_thesis_chair_and_mirrors_for_a_turned_frame', 'pytest.approx(b["reverse"]["rule_speed_m_s"], rel=1e-9)'),
        ('test_set_on_a_layout_file_reaches_the_report_as_the_short_forms_set', 'pytest.approx(float(y), rel=1e-9)'),
    ],
    'tests/test_report_words.py': [
        ('test_steady_turn_is_read_from_the_valid_part_only', 'pytest.approx(u * 3.0, rel=1e-6)'),
    ],
    'tests/test_rootlocus.py': [
        ('test_branches_are_continuous', 'np.abs(np.diff(eig, axis=0)).sum() <= np.abs(np.diff(raw, axis=0)).sum() + 1e-9'),
    ],
    'tests/test_search.py': [
        ('test_stop_at_level_changes_nothing_before_the_stop', 'np.abs(st_stop[hit, 1] - full[hit, 3]) <= 0.001 + 1e-12'),
        ('test_new_search_equals_the_bisection_where_reaching_is_monotone', 'abs(math.log(b.impulse_Ns / a.impulse_Ns)) <= math.log1p(TOL) * (1 + 1e-9)'),
        ('test_a_chair_that_reaches_the_level_whatever_the_push_is_settled_in_a_few_runs', 'abs(t[0] - t[1]) < 0.1'),
    ],
    'tests/test_search_rate_fit.py': [
        ('test_rate_fit_inverts_the_escape_law', 'abs(pred - exact) <= 100 * bound'),
        ('test_growth_rate_is_the_simulators_own_linearisation_and_the_steps_unchanged', 'abs(g / max(np.linalg.eigvals(sim.A).real) - 1.0) <= 1e3 * EPS / h'),
        ('test_simulated_escape_matches_docs_and_slope_is_one_over_the_growth_rate', 'np.testing.assert_allclose(s.t_level, [2.35, 2.74, 3.07], atol=0.005)'),
        ('test_simulated_escape_matches_docs_and_slope_is_one_over_the_growth_rate', 'pytest.approx(1.0 / growth[0], rel=0.10)'),
        ('test_simulated_escape_matches_docs_and_slope_is_one_over_the_growth_rate', 'pytest.approx(3.263, abs=5e-4)'),
        ('test_preset_problem_counts_quoted_in_docs_studies_md', 'pytest.approx(120, rel=0.05)'),
        ('test_preset_problem_counts_quoted_in_docs_studies_md', 'pytest.approx(298, rel=0.05)'),
    ],
    'tests/test_shimmy.py': [
        ('test_describing_function_threshold_matches_simulation', 'abs(math.sqrt(lo * hi) / a_star - 1) < 0.03'),
    ],
    'tests/test_shimmy_band.py': [
        ('test_band_agrees_with_a_trail_scan', 'min((abs(t - x) for x in band.boundaries_m[0]), default=1.0) < 1e-6'),
    ],
    'tests/test_shimmy_chair.py': [
        ('test_sigma_to_zero_recovers_rigid_tire_eigenvalues', 'np.testing.assert_allclose(fast.real, -U / sigma, rtol=1e-2)'),
        ('test_real_chair_critical_trail_close_to_towed_wheel', 'np.testing.assert_allclose(crit, comp.relaxation_length, atol=1e-3)'),
        ('test_mirror_symmetry', 'np.allclose(A1, A2)'),
        ('test_characteristic_polynomial_against_newton_euler', 'np.testing.assert_allclose(np.array(ours) / scale, np.array(exact) / scale, rtol=0, atol=1'),
        ('test_generation_reproduces_committed_file', 'np.allclose(_flat(fa(*args)), _flat(fb(*args)), rtol=1e-10)'),
        ('test_cli_chair_model_option', 'np.testing.assert_allclose(cm["compliant_pin"]["critical_trail_m"], out["critical_trail_m"'),
    ],
    'tests/test_shimmy_layout.py': [
        ('test_a_row_changes_its_trail_together', 'abs(x - lay.casters[0].x) < 1e-9'),
    ],
    'tests/test_simulate.py': [
        ('test_adaptive_converges_when_tolerances_are_halved', 'abs(ra - rb) < 0.005 * abs(rb)'),
        ('test_adaptive_stick_slip', 'np.abs(m[stuck]) <= 0.1 * (1 + 1e-6)'),
        ('test_adaptive_stick_slip', 'pytest.approx(w.first_time_abs_yaw_rate(1.0), rel=0.05)'),
        ('test_step_stability_limit_against_the_adaptive_scheme', 'pytest.approx(peak_ada, rel=0.08)'),
    ],
    'tests/test_simulate_slope.py': [
        ('test_plane_loads_at_zero_slope_are_eq_6_25', 'np.testing.assert_allclose(msl.normal_loads_plane(p, fx, fy, gn, *trig), msl.normal_loads('),
        ('test_grade_speed_closed_form', 'np.testing.assert_allclose(res.u, 0.75 + a * res.t, rtol=1e-10, atol=1e-12)'),
        ('test_grade_speed_closed_form', 'np.testing.assert_allclose(res.x, 0.75 * res.t + 0.5 * a * res.t ** 2, rtol=1e-9, atol=1e-'),
        ('test_grade_speed_closed_form', 'np.max(np.abs(res.heading)) < 1e-12'),
    ],
    'tests/test_slope.py': [
        ('test_front_caster_turn_rate_near_free_caster_closed_form', 'pytest.approx(g2 / U, rel=0.1)'),
    ],
    'tests/test_stick_slip.py': [
        ('test_critical_impulse_is_step_converged_with_stick_slip', 'abs(math.log(coarse.impulse_Ns / fine.impulse_Ns)) < 0.01'),
        ('test_critical_impulse_with_stick_slip_equals_the_adaptive_schemes', 'abs(math.log(fixed.impulse_Ns / adaptive.impulse_Ns)) < 0.01'),
        ('test_a_settled_run_never_reaches_the_level', 'abs(y[-1] - y[len(y) // 2]) < 1e-3'),
    ],
    'tests/test_study.py': [
        ('test_maps_use_one_batch', 'pytest.approx(0.75, abs=0.01)'),
        ('test_linear_overlay_matches_frictionless_simulation', 'pytest.approx(r_sim, rel=0.08)'),
        ('test_linear_overlay_matches_frictionless_simulation', 'pytest.approx(y_sim, rel=0.15, abs=0.005)'),
        ('test_reduced_mass_figure_8_14_is_not_reproduced_and_why', 'pytest.approx(r_ref, rel=0.03)'),
        ('test_reduced_mass_figure_8_14_is_not_reproduced_and_why', 'pytest.approx(r_light / r_ref, abs=0.005)'),
        ('test_studies_never_integrate_with_an_unstable_step', 'pytest.approx(np.max(np.abs(ref.yaw_rate)), rel=0.03)'),
    ],
    'tests/test_study_measures.py': [
        ('test_critical_impulse_frictionless_linear_limit', 'pytest.approx(predicted, rel=0.02)'),
        ('test_growth_rate_elasticities_closed_form_free_caster_mode', 'pytest.approx(expected, abs=0.02)'),
    ],
    'tests/test_sweep.py': [
        ('test_rows_equal_the_library_and_a_bad_chair_is_a_row', 'pytest.approx(locked[0], abs=5e-7 + 1e-10)'),
    ],
    'tests/test_sweep_layouts.py': [
        ('test_the_thesis_chair_swept_as_a_layout_gives_the_short_forms_rows', 'pytest.approx(b[col], rel=1e-9, abs=1e-12)'),
        ('test_a_frame_turned_round_sweeps_backwards_as_it_does_forwards', 'pytest.approx(fwd[1]["growth_rate_1_s"], rel=1e-3)'),
        ('test_random_draws_of_a_layout_are_the_short_forms_draws', 'pytest.approx(b[col], rel=1e-9, abs=1e-12)'),
    ],
    'tests/test_thesis_chapter8.py': [
        ('test_initial_lateral_velocity_equivalent_to_the_impulse', 'pytest.approx(ti, rel=0.10)'),
        ('test_initial_lateral_velocity_equivalent_to_the_impulse', 'pytest.approx(imp.at(t)["yaw_rate"], rel=0.25)'),
        ('test_front_caster_chair_under_a_constant_side_force_turns_steadily', 'pytest.approx(rates[6.0], rel=0.15)'),
        ('test_front_caster_chair_equals_the_thesis_trick', 'np.max(np.abs(a.yaw_rate + b.yaw_rate)) < 1e-4 * peak'),
        ('test_chapter9_revised_design_and_friction', 'pytest.approx(t_ref, rel=0.15)'),
        ('test_chapter9_revised_design_and_friction', 'pytest.approx(t_ref, rel=0.15)'),
    ],
    'tests/test_tires.py': [
        ('test_rolling_resistance_cubic_and_table_3_2', 'pytest.approx(t.rolling_coefficient_linear, rel=0.2)'),
    ],
    'tests/test_uncertain_nonlinear.py': [
        ('test_zero_spread_gives_exactly_the_nominal_values', 'abs(eq.speed - REFERENCE_SPEED) < FAST["tol"]'),
        ('test_small_spread_lies_between_the_end_chairs_and_widens_with_the_spread', 'abs(narrow.median - nominal) < 0.05 * nominal'),
    ],
    'tests/test_uncertainty.py': [
        ('test_monte_carlo_interval_matches_delta_method_on_linear_function', 'pytest.approx(sigma, rel=1e-7)'),
        ('test_monte_carlo_interval_matches_delta_method_on_linear_function', 'pytest.approx(mean - 1.96 * sigma, abs=4 * se)'),
        ('test_monte_carlo_interval_matches_delta_method_on_linear_function', 'pytest.approx(mean + 1.96 * sigma, abs=4 * se)'),
        ('test_monte_carlo_vs_delta_on_the_chair_model', 'pytest.approx(d.value, abs=0.1 * d.std)'),
        ('test_vector_outputs_and_nan_rows', 'pytest.approx(C.s1 - norm.ppf(0.95) * 0.01, abs=0.001)'),
    ],
    'tests/test_validation.py': [
        ('test_measured_rate_on_known_signals', 'pytest.approx(-0.4, rel=1e-6)'),
        ('test_caster_drag_acts_as_rear_cornering_stiffness', 'np.testing.assert_allclose(sim, closed, rtol=0.025)'),
        ('test_caster_drag_acts_as_rear_cornering_stiffness', 'np.testing.assert_allclose(no_drag, linear.massless_caster_rate(c, speeds), rtol=0.01)'),
    ],
    'tests/ui/test_app_tracking.py': [
        ('test_a_scripted_operator_of_known_delay_is_measured', 'pytest.approx(tau, rel=0.10)'),
    ],
}
