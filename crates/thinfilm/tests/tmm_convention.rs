//! `iridis_thinfilm::tmm` (tmm's calling convention, used by the Python drop-in `iridis.tmm`) against the `tmm`
//! package on the committed 1184-case fixture (`tools/gen_thinfilm_fixtures.py`): r, t, R and tmm's T — the
//! flux into the last medium, also when it absorbs — and against tmm's `inc_tmm` / `inc_absorp_in_each_layer`
//! (`tools/gen_incoherent_fixtures.py`).

use iridis_thinfilm::tmm::{coh_tmm, coh_tmm_batch, inc_tmm, Indices, Pol};
use iridis_thinfilm::{Complex64, Stack};
use serde_json::Value;

fn lists(stack: &str) -> (Vec<Complex64>, Vec<f64>) {
    let s = Stack::parse(stack).unwrap();
    let n: Vec<Complex64> = s.materials().map(|m| m.index_at(550.0).unwrap()).collect();
    let mut d = vec![f64::INFINITY];
    d.extend(s.thicknesses());
    d.push(f64::INFINITY);
    (n, d)
}

use crate::common::{complex as c, fixture};

#[test]
fn coh_tmm_agrees_with_tmm_on_the_fixture() {
    let doc: Value = fixture("tmm_reference.json");
    let (mut worst, mut count, mut absorbing) = (0.0f64, 0, 0);
    for case in doc["cases"].as_array().unwrap() {
        if case["kind"] == "seed" {
            continue; // dispersive (Aspnes Si): not one constant index per medium
        }
        let (n, d) = lists(case["stack"].as_str().unwrap());
        let (w, th) = (case["wavelength_nm"].as_f64().unwrap(), case["angle_rad"].as_f64().unwrap());
        absorbing += usize::from(case["absorbing_substrate"].as_bool().unwrap());
        for pol in [Pol::S, Pol::P] {
            let x = coh_tmm(pol, &n, &d, th, w).unwrap();
            let r = &case[pol.name()];
            let diffs = [
                (x.r - c(&r["r"])).norm(),
                (x.t - c(&r["t"])).norm(),
                (x.big_r - r["R"].as_f64().unwrap()).abs(),
                (x.big_t - r["T"].as_f64().unwrap()).abs(),
            ];
            let m = diffs.iter().fold(0.0f64, |a, b| a.max(*b));
            assert!(m < 1e-9, "{} λ={w} θ={th} {}: {diffs:?}", case["stack"], pol.name());
            worst = worst.max(m);
            count += 1;
        }
    }
    assert!(count >= 2 * 1060 && absorbing > 100, "{count} cases, {absorbing} absorbing substrates");
    eprintln!("coh_tmm vs tmm: worst |Δ| {worst:.2e} over {count} cases");
}

#[test]
fn batch_agrees_with_tmm_on_one_stack_at_many_points() {
    // The fixture's stacks at their own points, run as batches of one stack each; plus the same stack over
    // a grid, checked point by point against single calls (which the test above ties to tmm).
    let doc: Value = fixture("tmm_reference.json");
    for case in doc["cases"].as_array().unwrap().iter().filter(|c| c["kind"] != "seed").take(200) {
        let (n, d) = lists(case["stack"].as_str().unwrap());
        let (w, th) = (case["wavelength_nm"].as_f64().unwrap(), case["angle_rad"].as_f64().unwrap());
        for pol in [Pol::S, Pol::P] {
            let b = coh_tmm_batch(pol, Indices::Constant(&n), &d, &[th; 5], &[w; 5]).unwrap();
            let r = &case[pol.name()];
            for i in 0..5 {
                assert!((b.r[i] - c(&r["r"])).norm() < 1e-9, "{} {}", case["stack"], pol.name());
                assert!((b.big_t[i] - r["T"].as_f64().unwrap()).abs() < 1e-9);
            }
        }
    }
}

#[test]
fn inc_tmm_agrees_with_tmm() {
    let doc: Value = fixture("tmm_incoherent.json");
    let mut worst = 0.0f64;
    for case in doc["inc"].as_array().unwrap() {
        let text = case["stack"].as_str().unwrap();
        let s = Stack::parse(text).unwrap();
        let (n, d) = lists(text);
        let mut cl = vec!['i'];
        cl.extend(s.layers.iter().map(|l| if l.incoherent { 'i' } else { 'c' }));
        cl.push('i');
        let (w, th) = (case["wavelength_nm"].as_f64().unwrap(), case["angle_rad"].as_f64().unwrap());
        for pol in [Pol::S, Pol::P] {
            let x = inc_tmm(pol, &n, &d, &cl, th, w).unwrap();
            let r = &case[pol.name()];
            let refa: Vec<f64> = r["absorp"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
            assert_eq!(refa.len(), x.absorp.len());
            let mut m = (x.big_r - r["R"].as_f64().unwrap()).abs().max((x.big_t - r["T"].as_f64().unwrap()).abs());
            for (a, b) in x.absorp.iter().zip(&refa) {
                m = m.max((a - b).abs());
            }
            assert!(m < 1e-9, "{text} λ={w} θ={th} {}: worst {m}", pol.name());
            worst = worst.max(m);
        }
    }
    eprintln!("inc_tmm vs tmm: worst |Δ| {worst:.2e}");
}
