//! Preparation: levelling (AFM scans carry a tilt and line-to-line offsets), cropping, resampling, tiling,
//! padding. Every function returns a new field and appends what it did to `meta.notes`.

use crate::{check_dims, check_pixel, HeightField, SurfaceError};

fn with(hf: &HeightField, rows: usize, cols: usize, dx: f64, dy: f64, h: Vec<f64>, note: String) -> HeightField {
    let mut meta = hf.meta.clone();
    meta.notes.push(note);
    HeightField { rows, cols, dx_nm: dx, dy_nm: dy, heights_nm: h, meta }
}

/// Subtracts the mean height (a constant phase for diffraction, but it shrinks `|h|max` and so the number
/// of Taylor terms).
pub fn remove_mean(hf: &HeightField) -> HeightField {
    let m = hf.mean();
    let h = hf.heights_nm.iter().map(|x| x - m).collect();
    with(hf, hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, h, format!("mean {m:.3} nm removed"))
}

/// Subtracts the least-squares plane `a + b·x + c·y` (the sample tilt of an AFM scan); the result has zero
/// mean.
pub fn level_plane(hf: &HeightField) -> HeightField {
    // Centred coordinates make the normal equations diagonal: the three fits are independent.
    let (rows, cols) = (hf.rows, hf.cols);
    let (xc, yc) = ((cols as f64 - 1.0) / 2.0, (rows as f64 - 1.0) / 2.0);
    let (mut sx, mut sy, mut sxx, mut syy) = (0.0, 0.0, 0.0, 0.0);
    let mean = hf.mean();
    for r in 0..rows {
        let y = yc - r as f64;
        for c in 0..cols {
            let x = c as f64 - xc;
            let h = hf.heights_nm[r * cols + c] - mean;
            sx += x * h;
            sy += y * h;
            sxx += x * x;
            syy += y * y;
        }
    }
    let (b, c) = (sx / sxx, sy / syy);
    let mut h = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        let y = yc - r as f64;
        for col in 0..cols {
            let x = col as f64 - xc;
            h.push(hf.heights_nm[r * cols + col] - mean - b * x - c * y);
        }
    }
    with(
        hf,
        rows,
        cols,
        hf.dx_nm,
        hf.dy_nm,
        h,
        format!("plane levelled (slopes {:.4e} along x, {:.4e} along y)", b / hf.dx_nm, c / hf.dy_nm),
    )
}

/// Subtracts each row's mean (AFM scan-line levelling: every fast-scan line gets its own offset), then the
/// overall mean. Destroys structure that varies only along y; use it on scans with visible line steps.
pub fn level_rows(hf: &HeightField) -> HeightField {
    let mut h = Vec::with_capacity(hf.heights_nm.len());
    for r in 0..hf.rows {
        let row = hf.row(r);
        let m = row.iter().sum::<f64>() / row.len() as f64;
        h.extend(row.iter().map(|x| x - m));
    }
    with(hf, hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, h, "rows levelled by their means".into())
}

/// Median line correction (Gwyddion's "Align Rows", median): subtracts each scan line's median, then the
/// overall mean. Unlike the row mean, a median is not pulled by a particle or a spike on the line.
pub fn level_lines_median(hf: &HeightField) -> HeightField {
    let mut h = Vec::with_capacity(hf.heights_nm.len());
    for r in 0..hf.rows {
        let row = hf.row(r);
        let mut s = row.to_vec();
        s.sort_by(f64::total_cmp);
        let n = s.len();
        let med = if n % 2 == 1 { s[n / 2] } else { 0.5 * (s[n / 2 - 1] + s[n / 2]) };
        h.extend(row.iter().map(|x| x - med));
    }
    let m = h.iter().sum::<f64>() / h.len() as f64;
    h.iter_mut().for_each(|x| *x -= m);
    with(hf, hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, h, "scan lines levelled by their medians".into())
}

/// Subtracts the least-squares polynomial of total degree 2 in x and y (`1, x, y, x², xy, y²`): the bow of a
/// piezo scanner's arc on top of the tilt.
pub fn level_poly(hf: &HeightField) -> HeightField {
    let (rows, cols) = (hf.rows, hf.cols);
    // Coordinates scaled to [-1, 1] keep the normal equations well conditioned.
    let sx = 2.0 / (cols.max(2) - 1) as f64;
    let sy = 2.0 / (rows.max(2) - 1) as f64;
    let basis = |r: usize, c: usize| {
        let (x, y) = (c as f64 * sx - 1.0, 1.0 - r as f64 * sy);
        [1.0, x, y, x * x, x * y, y * y]
    };
    let mut a = [[0.0f64; 7]; 6];
    for r in 0..rows {
        for c in 0..cols {
            let b = basis(r, c);
            let z = hf.heights_nm[r * cols + c];
            for i in 0..6 {
                for j in 0..6 {
                    a[i][j] += b[i] * b[j];
                }
                a[i][6] += b[i] * z;
            }
        }
    }
    // Gauss–Jordan with partial pivoting; a degenerate system (a 2-row field) keeps those terms at 0.
    for col in 0..6 {
        let piv = (col..6).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs())).unwrap_or(col);
        a.swap(col, piv);
        let p = a[col][col];
        if p.abs() < 1e-12 {
            continue;
        }
        for k in col..7 {
            a[col][k] /= p;
        }
        for i in 0..6 {
            if i != col {
                let f = a[i][col];
                for k in col..7 {
                    a[i][k] -= f * a[col][k];
                }
            }
        }
    }
    let coef: Vec<f64> = (0..6).map(|i| if a[i][i].abs() > 0.5 { a[i][6] } else { 0.0 }).collect();
    let mut h = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        for c in 0..cols {
            let b = basis(r, c);
            h.push(hf.heights_nm[r * cols + c] - (0..6).map(|i| coef[i] * b[i]).sum::<f64>());
        }
    }
    with(hf, rows, cols, hf.dx_nm, hf.dy_nm, h, "polynomial (degree 2) levelled".into())
}

/// Levelling by name: `none`, `mean`, `plane`, `poly` (degree 2), `lines` (median line correction) or `rows`
/// (line means).
pub fn level_by_name(hf: &HeightField, how: &str) -> Result<HeightField, SurfaceError> {
    Ok(match how.trim() {
        "none" => hf.clone(),
        "mean" => remove_mean(hf),
        "plane" => level_plane(hf),
        "poly" => level_poly(hf),
        "lines" => level_lines_median(hf),
        "rows" => level_rows(hf),
        other => {
            return Err(SurfaceError::invalid(format!(
                "unknown levelling '{other}'; expected none, mean, plane, poly, lines or rows"
            )))
        }
    })
}

/// The levelling a SURFACE gets when none is asked: `plane` for a file, `none` for a built-in
/// ([`level_for_model`]).
pub fn default_level(spec: &str) -> &'static str {
    if spec.starts_with("builtin:") {
        "none"
    } else {
        "plane"
    }
}

/// Levelling before the diffraction model, as Gwyddion users expect: a file is plane-levelled unless the
/// user asks otherwise (a scan's tilt puts a false streak and lobes into BRDF maps); a built-in is left as
/// generated. Returns the field and a sentence saying what was done, for the command's output.
pub fn level_for_model(
    spec: &str,
    hf: HeightField,
    requested: Option<&str>,
) -> Result<(HeightField, String), SurfaceError> {
    let builtin = spec.starts_with("builtin:");
    let how = requested.unwrap_or(default_level(spec));
    let out = level_by_name(&hf, how)?;
    let why = match (requested, builtin) {
        (Some(_), _) => format!("as asked: --level {how}"),
        (None, false) => "the default for files; --level none keeps the tilt".to_string(),
        (None, true) => "built-ins are used as generated".to_string(),
    };
    Ok((out, format!("levelling: {how} ({why})")))
}

/// The block starting at `(row0, col0)` of `rows × cols` samples.
pub fn crop(hf: &HeightField, row0: usize, col0: usize, rows: usize, cols: usize) -> Result<HeightField, SurfaceError> {
    check_dims(rows, cols)?;
    if row0.saturating_add(rows) > hf.rows || col0.saturating_add(cols) > hf.cols {
        return Err(SurfaceError::invalid(format!(
            "crop {rows}×{cols} at row {row0}, column {col0} does not fit in {}×{}",
            hf.rows, hf.cols
        )));
    }
    let mut h = Vec::with_capacity(rows * cols);
    for r in row0..row0 + rows {
        h.extend_from_slice(&hf.row(r)[col0..col0 + cols]);
    }
    Ok(with(hf, rows, cols, hf.dx_nm, hf.dy_nm, h, format!("cropped to {rows}×{cols} at ({row0}, {col0})")))
}

/// Resamples to new pixel sizes keeping the physical extent (rounded to whole pixels). Bilinear
/// interpolation; when coarsening, each output sample first averages the input pixels it covers, so fine
/// structure does not alias into false periods.
pub fn resample(hf: &HeightField, dx_nm: f64, dy_nm: f64) -> Result<HeightField, SurfaceError> {
    check_pixel(dx_nm, dy_nm)?;
    let (ex, ey) = hf.extent_nm();
    let cols_f = (ex / dx_nm).round();
    let rows_f = (ey / dy_nm).round();
    if cols_f > crate::MAX_DIM as f64 || rows_f > crate::MAX_DIM as f64 {
        return Err(SurfaceError::invalid(format!("resampling to {dx_nm} nm gives too many samples")));
    }
    let (rows, cols) = (rows_f.max(0.0) as usize, cols_f.max(0.0) as usize);
    check_dims(rows, cols)?;
    let (dx, dy) = (ex / cols as f64, ey / rows as f64);
    // Box pre-filter width in input pixels (≥ 1).
    let (kx, ky) = ((dx / hf.dx_nm).max(1.0), (dy / hf.dy_nm).max(1.0));
    let src = if kx > 1.5 || ky > 1.5 {
        box_blur(hf, kx.round() as usize, ky.round() as usize)
    } else {
        hf.heights_nm.clone()
    };
    let sample = |r: f64, c: f64| -> f64 {
        let r = r.clamp(0.0, (hf.rows - 1) as f64);
        let c = c.clamp(0.0, (hf.cols - 1) as f64);
        let (r0, c0) = (r.floor() as usize, c.floor() as usize);
        let (r1, c1) = ((r0 + 1).min(hf.rows - 1), (c0 + 1).min(hf.cols - 1));
        let (fr, fc) = (r - r0 as f64, c - c0 as f64);
        let g = |r: usize, c: usize| src[r * hf.cols + c];
        (1.0 - fr) * ((1.0 - fc) * g(r0, c0) + fc * g(r0, c1)) + fr * ((1.0 - fc) * g(r1, c0) + fc * g(r1, c1))
    };
    let mut h = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        // Pixel centres: input pixel i covers [i·d, (i+1)·d].
        let rin = (r as f64 + 0.5) * dy / hf.dy_nm - 0.5;
        for c in 0..cols {
            let cin = (c as f64 + 0.5) * dx / hf.dx_nm - 0.5;
            h.push(sample(rin, cin));
        }
    }
    Ok(with(
        hf,
        rows,
        cols,
        dx,
        dy,
        h,
        format!("resampled from {}×{} nm to {dx:.3}×{dy:.3} nm pixels", hf.dx_nm, hf.dy_nm),
    ))
}

fn box_blur(hf: &HeightField, kx: usize, ky: usize) -> Vec<f64> {
    let (rows, cols) = (hf.rows, hf.cols);
    let mean_of = |n: usize, k: usize, i: usize, get: &dyn Fn(usize) -> f64| -> f64 {
        let lo = i.saturating_sub(k / 2);
        let hi = (i + k - k / 2).min(n);
        (lo..hi).map(get).sum::<f64>() / (hi - lo) as f64
    };
    let mut a = vec![0.0; rows * cols];
    for r in 0..rows {
        for c in 0..cols {
            a[r * cols + c] = mean_of(cols, kx, c, &|j| hf.heights_nm[r * cols + j]);
        }
    }
    let mut b = vec![0.0; rows * cols];
    for r in 0..rows {
        for c in 0..cols {
            b[r * cols + c] = mean_of(rows, ky, r, &|j| a[j * cols + c]);
        }
    }
    b
}

/// Repeats the field `ny` times down and `nx` times across (a patch smaller than the coherence area,
/// made periodic on purpose).
pub fn tile(hf: &HeightField, ny: usize, nx: usize) -> Result<HeightField, SurfaceError> {
    if ny == 0 || nx == 0 {
        return Err(SurfaceError::invalid("tile counts must be at least 1"));
    }
    let rows = hf.rows.checked_mul(ny).ok_or_else(|| SurfaceError::invalid("tiling overflows"))?;
    let cols = hf.cols.checked_mul(nx).ok_or_else(|| SurfaceError::invalid("tiling overflows"))?;
    check_dims(rows, cols)?;
    let mut h = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        let src = hf.row(r % hf.rows);
        for _ in 0..nx {
            h.extend_from_slice(src);
        }
    }
    Ok(with(hf, rows, cols, hf.dx_nm, hf.dy_nm, h, format!("tiled {ny}×{nx}")))
}

/// Pads to `rows × cols` (centred) with the field's mean height, e.g. to a fast FFT size or to the coherence
/// area without inventing structure.
pub fn pad(hf: &HeightField, rows: usize, cols: usize) -> Result<HeightField, SurfaceError> {
    check_dims(rows, cols)?;
    if rows < hf.rows || cols < hf.cols {
        return Err(SurfaceError::invalid(format!(
            "cannot pad {}×{} to the smaller {rows}×{cols}; crop instead",
            hf.rows, hf.cols
        )));
    }
    let m = hf.mean();
    let (r0, c0) = ((rows - hf.rows) / 2, (cols - hf.cols) / 2);
    let mut h = vec![m; rows * cols];
    for r in 0..hf.rows {
        h[(r + r0) * cols + c0..(r + r0) * cols + c0 + hf.cols].copy_from_slice(hf.row(r));
    }
    Ok(with(hf, rows, cols, hf.dx_nm, hf.dy_nm, h, format!("padded to {rows}×{cols} with the mean {m:.3} nm")))
}
