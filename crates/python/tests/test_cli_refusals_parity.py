"""Where the CLI refuses a combination of options, or says a warning or a note, Python does the same: the
differences an audit of every function's defaults against its command's found (2026-11-29), each fixed."""
import logging
import os

import pytest

import iridis.diffraction as diffraction
import iridis.film as film
import iridis.surface as surface
import iridis.thinfilm as thinfilm

SINE = "builtin:sine?size=4um&pixel=100nm"


def test_grating_refuses_a_method_with_compare():
    # The CLI: "the argument '--method <METHOD>' cannot be used with '--compare'"; the method was ignored here.
    with pytest.raises(ValueError, match=r"method would be ignored: compare runs both"):
        diffraction.grating(SINE, 0.0, 550, method="rigorous", compare=True)


def test_brdf_map_run_refuses_an_exposure_with_auto_exposure():
    with pytest.raises(ValueError, match=r"exposure 2000 would be ignored: auto_exposure chooses"):
        diffraction.brdf_map_run(SINE, size=16, method="reference", auto_exposure=True, exposure_ru=2000)


def test_fit_refuses_sigma_with_weights(tmp_path):
    measured = tmp_path / "measured.csv"
    measured.write_text(film.spectrum("air | SiO2 110nm | Si", from_nm=400, to_nm=700, step_nm=10).csv)
    stack = "air | SiO2 {d=100nm:50nm..300nm} | Si"
    with pytest.raises(ValueError, match=r"sigma and weights say the same .*give one"):
        film.fit(measured, stack, sigma="0.01", weights="1")
    assert abs(film.fit(measured, stack, sigma="0.01")["values"][0] - 110.0) < 0.01


def test_brdf_vision_logs_the_notes_the_cli_prints(caplog):
    with caplog.at_level(logging.INFO, logger="iridis"):
        v = diffraction.vision(SINE, "bluetit", views_deg=[0.0, 10.0])
    notes = [n for n in v["vision"]["notes"]]
    assert notes and all(any(n in r.getMessage() for r in caplog.records) for n in notes), (notes, caplog.text)


def test_a_coarse_grid_for_a_thick_film_warns_at_the_callers_line():
    # 50 µm of water: fringes 1.09 nm apart at 380 nm, under the 5 nm grid (the CLI's warning).
    with pytest.warns(UserWarning, match=r"layer 1 \(water 50000 nm\) makes interference fringes 1.09 nm apart") as w:
        thinfilm.Stack("air | water 50000nm | air").color()
    assert os.path.samefile(w[0].filename, __file__), w[0].filename
    # A library warning through a decorated wrapper is the caller's line too, not the decorator's.
    with pytest.warns(UserWarning) as w:
        diffraction.brdf_eval(SINE, 0.0, 0.0, method="reference")
    assert all(os.path.samefile(x.filename, __file__) for x in w), [x.filename for x in w]


def test_surface_info_warns_as_the_cli_does():
    s = surface.load(SINE)
    with pytest.warns(UserWarning, match=r"pixel size 100.0 nm is coarser than") as w:
        info = s.info()
    assert [str(x.message) for x in w] == info["warnings"]
    with pytest.warns(UserWarning, match=r"pixel size 100.0 nm is coarser than"):
        s.info_text()
