"""`python -m iridis.bench` at small size: it runs, checks iridis against tmm before timing, and reports the
figures docs/python.md quotes (no timing is asserted: tests never depend on wall-clock time)."""
import json

import pytest

pytest.importorskip("tmm")

from iridis import bench  # noqa: E402


def test_bench_runs_small_and_reports_agreement_with_tmm(capsys):
    bench.main(["--points", "2000", "--tmm-points", "200", "--calls", "60", "--json"])
    out = json.loads(capsys.readouterr().out)
    b = out["batch"]
    assert b["points"] == 2000 and b["tmm_points_timed"] == 200
    assert b["worst_abs_diff_R"] < 1e-9  # coh_tmm_batch against a loop of tmm.coh_tmm on the same points
    assert {"iridis_s", "tmm_s", "iridis_cpu_s", "tmm_cpu_s", "speedup", "speedup_cpu"} <= set(b)
    assert [r["stack"] for r in out["call_by_call"]] == ["3 layers", "10 layers"]
    tf = b["tmm_fast"]
    assert "skipped" in tf or tf["worst_abs_diff_R"] < 1e-9
    ab = out["absorbing"]  # issue 29's absorbing stack, 2000 wavelengths at one angle
    assert ab["points"] == 2000 and ab["worst_abs_diff_R"] < 1e-9
