// Phases as fixed-point fractions of a turn: a u32 p stands for the angle 2 pi p / 2^32. Sums and integer
// multiples of such phases are exact (u32 arithmetic wraps, which is "mod one turn"), so a phase that reaches
// thousands of turns -- k (u x + v y) over a large patch -- keeps its fraction to 2^-32 of a turn, where an f32
// would keep ~1e-4 of a turn at 1000 turns. Shared by the ground-truth shader and its accuracy test;
// the scene shader's noise hash multiplies with mul32.

// The 64-bit product a * b as (low word, high word), in 16-bit halves.
fn mul32(a: u32, b: u32) -> vec2<u32> {
    let a0 = a & 0xffffu;
    let a1 = a >> 16u;
    let b0 = b & 0xffffu;
    let b1 = b >> 16u;
    let p00 = a0 * b0;
    let p01 = a0 * b1;
    let p10 = a1 * b0;
    let p11 = a1 * b1;
    let mid = (p00 >> 16u) + (p01 & 0xffffu) + (p10 & 0xffffu);
    return vec2<u32>((p00 & 0xffffu) | (mid << 16u), p11 + (p01 >> 16u) + (p10 >> 16u) + (mid >> 16u));
}

// The high 32 bits of the 64-bit product a * b.
fn mulhi(a: u32, b: u32) -> u32 {
    return mul32(a, b).y;
}

// frac(alpha * i) in 2^-32 turns, alpha a 0.64 fixed-point fraction of a turn given as (low word, high word):
// exact but for the truncated low product (< 2^-32 turn).
fn turns_times(alpha: vec2<u32>, i: u32) -> u32 {
    return alpha.y * i + mulhi(alpha.x, i);
}

// A phase x (turns, f32, |x| < 2^22) as a fixed-point fraction: x - round(x) is exact in f32, then 2^-31 steps.
fn turns_of(x: f32) -> u32 {
    let f = x - round(x);
    return bitcast<u32>(i32(round(f * 2147483648.0))) << 1u;
}

// (cos, sin) of 2 pi p / 2^32: the octant from the top three bits (exact), the angle within it (at most
// pi/4) measured from the nearest multiple of pi/2, Taylor polynomials to x^9 and x^10 (truncation < 2e-9 at
// pi/4), so the error is the f32 rounding of that angle (< 5e-8 rad) and of the polynomials -- whatever the
// driver's sin and cos do far from zero (Vulkan asks only 2^-11 of them on [-pi, pi]).
fn cis_turns(p: u32) -> vec2<f32> {
    let octant = p >> 29u;
    let odd = (octant & 1u) == 1u;
    var r = p & 0x1fffffffu;
    if (odd) {
        r = 0x20000000u - r;
    }
    let x = f32(r) * 1.4629180792671596e-9; // 2 pi / 2^32
    let x2 = x * x;
    let s = x + x * x2 * (-0.16666666666666666 + x2 * (0.008333333333333333 + x2 * (-0.0001984126984126984
        + x2 * 2.7557319223985893e-6)));
    let c = 1.0 + x2 * (-0.5 + x2 * (0.041666666666666664 + x2 * (-0.001388888888888889 + x2
        * (2.48015873015873e-5 - x2 * 2.755731922398589e-7))));
    // The angle is q quarter turns plus psi, psi = x (even octants) or -x (odd ones): (cos, sin) of psi turned
    // by q quarter turns, without branches (one quarter turn: (c, s) -> (-s, c); two: negation).
    let sp = select(s, -s, odd);
    let q = ((octant + 1u) >> 1u) & 3u;
    let turned = select(vec2<f32>(c, sp), vec2<f32>(-sp, c), (q & 1u) != 0u);
    return select(turned, -turned, (q & 2u) != 0u);
}
