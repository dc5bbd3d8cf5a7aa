//! Scratch probe: where the cranks part.
#[path = "../tests/mechanisms/mod.rs"]
mod mechanisms;
use mechanisms::*;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let n: usize = a[1].parse().unwrap();
    let crank = if a[2] == "u" {
        CrankMass::Uniform
    } else {
        CrankMass::AtPin
    };
    let h: f64 = a[3].parse().unwrap();
    let tol: f64 = a[4].parse().unwrap();
    let t_end: f64 = a[5].parse().unwrap();
    let t0 = std::time::Instant::now();
    let table = forward(&parallelogram_chain(n, 0.0, false, crank), h, tol, t_end).unwrap();
    let th0 = table.channel("crank0.phi").unwrap();
    let mut worst = (0.0f64, 0.0f64, 0usize);
    let mut worst_nb = (0.0f64, 0.0f64);
    for (r, t) in table.t.iter().enumerate() {
        let mut s = 0.0f64;
        let mut kk = 0;
        for k in 1..=n {
            let d = (table.channel(&format!("crank{k}.phi")).unwrap()[r] - th0[r]).abs();
            if d > s {
                s = d;
                kk = k;
            }
        }
        let mut nb = 0.0f64;
        for k in 0..n {
            let d = (table.channel(&format!("crank{}.phi", k + 1)).unwrap()[r]
                - table.channel(&format!("crank{k}.phi")).unwrap()[r])
                .abs();
            nb = nb.max(d);
        }
        if nb > worst_nb.0 {
            worst_nb = (nb, *t);
        }
        if s > 1e-7 {
            println!(
                "  t={t:.2} th0={:.6} spread={s:.2e} neighbour={nb:.2e}",
                th0[r]
            );
        }
        if s > worst.0 {
            worst = (s, *t, kk);
        }
        if r % 10 == 0 {
            println!("t={t:.2} th0={:.5} spread={s:.2e} (crank {kk})", th0[r]);
        }
    }
    println!(
        "worst {:?} neighbour {:?} ({:.1} s)",
        worst,
        worst_nb,
        t0.elapsed().as_secs_f64()
    );
}
