use faer::Mat;
use num_complex::Complex64 as C;
use std::time::Instant;
fn main() {
    for n in [100usize, 200, 484, 900] {
        let a = Mat::<C>::from_fn(n, n, |i, j| {
            C::new(
                ((i * 7 + j * 13) % 17) as f64 / 17.0 + if i == j { 3.0 } else { 0.0 },
                ((i * 3 + j * 5) % 11) as f64 / 11.0,
            )
        });
        let t = Instant::now();
        let e = a.eigen().unwrap();
        let t1 = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let _v = a.eigenvalues().unwrap();
        let t2 = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let _x = a.partial_piv_lu();
        println!("n={n} eigen {t1:.3}s eigenvalues {t2:.3}s lu {:.4}s {}", t.elapsed().as_secs_f64(), e.S()[0]);
    }
}
