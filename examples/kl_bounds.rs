//! Lower bounds on the configurational KL divergence of schemes at one dt, from the shift of
//! two statistics of the configuration: the potential energy U and
//! S = sum_i |F^C_i|^2 - k_B T sum_i lap_i U, whose mean vanishes at equilibrium (it is the
//! numerator of T_C - k_B T). For any statistic f, KL(rho || pi) >= E_rho[f] - ln E_pi[e^f]
//! (Donsker-Varadhan); with f = lambda c . (U, S), c = Sigma^-1 Delta (Sigma the covariance of
//! (U, S) at equilibrium, Delta the shift of their means), maximised over lambda, the bound is
//! computed from Monte Carlo samples of pi and the scheme's mean shift. It checks the
//! estimates of `dpd kl` (docs/design.md): an estimate below the bound would be wrong.
//!
//! Usage: `cargo run --release -p dpd --example kl_bounds -- DT TIME RUNS SCHEME...` (standard box,
//! gamma = 4.5, N = 500; each run relaxes 20 time units, then samples every step for TIME).

use dpd::init::{cubic_box, maxwell_momenta, uniform_positions};
use dpd::metropolis::Metropolis;
use dpd::observe::thermo;
use dpd::{Params, PeriodicBox, System, Vec3};

type Error = Box<dyn std::error::Error + Send + Sync>;

fn arg<T: std::str::FromStr>(k: usize, what: &str) -> Result<T, Error> {
    let s = std::env::args()
        .nth(k)
        .ok_or_else(|| format!("argument {k} ({what}) missing; usage: DT TIME RUNS SCHEME..."))?;
    s.parse()
        .map_err(|_| format!("argument {k} ({what}) = {s:?} is not valid").into())
}

const N: usize = 500;

/// (U, S) of the configuration `q`.
fn statistics(params: &Params, bx: PeriodicBox, q: Vec<Vec3>) -> Result<[f64; 2], Error> {
    let mut sys = System::builder(params.clone(), bx, q).build()?;
    let t = thermo(&mut sys);
    let kbt = params.kbt();
    Ok([
        t.potential_energy * N as f64,
        t.config_numerator - kbt * t.config_denominator,
    ])
}

fn mean(xs: &[[f64; 2]]) -> [f64; 2] {
    let n = xs.len() as f64;
    [0, 1].map(|k| xs.iter().map(|x| x[k]).sum::<f64>() / n)
}

fn main() -> Result<(), Error> {
    let dt: f64 = arg(1, "DT")?;
    let time: f64 = arg(2, "TIME")?;
    let runs: u64 = arg(3, "RUNS")?;
    let schemes: Vec<String> = std::env::args().skip(4).collect();
    let params = Params::builder().gamma(4.5).build()?;
    let bx = cubic_box(N, 3.0)?;

    // Equilibrium: 4000 Monte Carlo samples, 5 sweeps apart.
    let mut chain = Metropolis::new(
        params.clone(),
        bx,
        &uniform_positions(&bx, N, 1),
        vec![0; N],
        1,
    )?;
    chain.equilibrate(300);
    let mut pi = Vec::new();
    for _ in 0..4000 {
        for _ in 0..5 {
            chain.sweep();
        }
        pi.push(statistics(&params, bx, chain.positions().to_vec())?);
    }
    let m = mean(&pi);
    let centred: Vec<[f64; 2]> = pi.iter().map(|x| [x[0] - m[0], x[1] - m[1]]).collect();
    let cov = |a: usize, b: usize| {
        centred.iter().map(|x| x[a] * x[b]).sum::<f64>() / centred.len() as f64
    };
    let (suu, sus, sss) = (cov(0, 0), cov(0, 1), cov(1, 1));
    println!(
        "equilibrium: U = {:.2}, S = {:.2}, sd(U) = {:.2}, sd(S) = {:.1}, corr = {:.3}",
        m[0],
        m[1],
        suu.sqrt(),
        sss.sqrt(),
        sus / (suu * sss).sqrt()
    );

    for name in &schemes {
        let scheme = dpd::schemes::registry::resolve(name)?;
        let mut samples = Vec::new();
        for seed in 1..=runs {
            let mut sys = System::builder(params.clone(), bx, uniform_positions(&bx, N, seed))
                .momenta(maxwell_momenta(&vec![1.0; N], 1.0, seed))
                .dt(dt)
                .seed(seed)
                .build()?;
            sys.advance(&*scheme, (20.0 / dt).round() as u64)?;
            for _ in 0..(time / dt).round() as u64 {
                sys.advance(&*scheme, 1)?;
                samples.push(statistics(&params, bx, sys.positions().to_vec())?);
            }
        }
        let r = mean(&samples);
        let delta = [r[0] - m[0], r[1] - m[1]];
        // c = Sigma^-1 Delta; the best linear statistic to second order.
        let det = suu * sss - sus * sus;
        let c = [
            (sss * delta[0] - sus * delta[1]) / det,
            (suu * delta[1] - sus * delta[0]) / det,
        ];
        let bound = |dir: [f64; 2]| {
            let shift = dir[0] * delta[0] + dir[1] * delta[1];
            (0..=400)
                .map(|k| {
                    let lambda = 0.01 * k as f64;
                    let mgf = centred
                        .iter()
                        .map(|x| (lambda * (dir[0] * x[0] + dir[1] * x[1])).exp())
                        .sum::<f64>()
                        / centred.len() as f64;
                    lambda * shift - mgf.ln()
                })
                .fold(0.0, f64::max)
        };
        // Beyond about three standard deviations along c, 4000 samples cannot estimate
        // E_pi[e^f] (its weight sits in the unsampled tail) and the bounds come out too high.
        let distance = (c[0] * delta[0] + c[1] * delta[1]).sqrt();
        if distance > 3.0 {
            println!(
                "{name} dt {dt}: shifted {distance:.1} standard deviations, bounds unreliable"
            );
        }
        println!(
            "{name} dt {dt}: Delta U = {:+.2} ({:+.3} sd), Delta S = {:+.1} ({:+.3} sd); \
             KL >= {:.3} (U), {:.3} (S), {:.3} (both), Gaussian 0.5 Delta.c = {:.3}",
            delta[0],
            delta[0] / suu.sqrt(),
            delta[1],
            delta[1] / sss.sqrt(),
            bound([delta[0].signum() / suu.sqrt(), 0.0]),
            bound([0.0, delta[1].signum() / sss.sqrt()]),
            bound(c),
            0.5 * (c[0] * delta[0] + c[1] * delta[1])
        );
    }
    Ok(())
}
