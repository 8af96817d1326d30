use abtrack_host_tests::encounters::*;
fn main() {
    for (i, e) in suite().into_iter().enumerate() {
        if !matches!(e.name, "offset-beyond-hmd" | "abeam-1.2nm") {
            continue;
        }
        let x = e.relative(0.0);
        let cpa = -(x.s[0] * x.v[0] + x.s[1] * x.v[1]) / (x.v[0] * x.v[0] + x.v[1] * x.v[1]);
        println!("cpa {cpa}");
        let mut durs = vec![];
        let mut n = 0;
        let mut after = 0;
        for run in 0..30 {
            let meas = measurements(&e, Noise::Seeded(derive_run_seed(i as u64, run as u64)));
            let out = run_library::<f64>(&e, &meas).unwrap();
            let t = timeline(&out);
            if let Some(on) = t.ra_onset_s {
                n += 1;
                let off = t.clear_of_conflict_s.unwrap_or(f64::NAN);
                durs.push((off - on) as i64);
                if !(off < cpa) {
                    println!("late off {off}");
                }
                if t.ra_scans as f64 != off - on {
                    after += 1;
                }
            }
        }
        durs.sort();
        println!("{} RAs {n} durations {:?} not-one {after}", e.name, durs);
    }
}
