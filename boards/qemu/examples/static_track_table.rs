//! A static f32 track table under cortex-m-rt on a Cortex-M4F: 32 tracks,
//! up to 32 measurements a scan, no heap. The table is a `static` (built by
//! the `const fn` `TrackTable::new`); three targets cross the sensor's
//! field, one scan a second, and after ten scans the table must hold three
//! confirmed tracks at the right places.
//!
//! The board support (the defmt log over semihosting, the panic handler,
//! the exit status) is this package's library, as in the firmware's
//! binaries. Runs under QEMU on the mps2-an386 board:
//!
//! ```text
//! cargo run --release --target thumbv7em-none-eabihf -p abtrack-firmware --example static_track_table
//! ```
//!
//! It ends with `static track table: 3 confirmed tracks, all within 1 m (…)`
//! and exit status 0, or an error line and exit status 1.
#![no_std]
#![no_main]

use abtrack::track::{
    Association, FixedGainTrack, Gate, Measurement, TrackStatus, TrackTable, TrackerConfig,
};
use abtrack::Gains;
use abtrack_firmware::board;

/// The table: 32 tracks, 32 measurements per scan, in f32 (the M4F's FPU).
type Table = TrackTable<f32, FixedGainTrack<f32>, 32, 32>;

/// The targets: start (x, y) in m and velocity (vx, vy) in m/s.
const TARGETS: [([f32; 2], [f32; 2]); 3] = [
    ([0.0, 1_000.0], [100.0, 0.0]),
    ([5_000.0, 0.0], [0.0, -50.0]),
    ([-3_000.0, -3_000.0], [60.0, 80.0]),
];
const SCANS: u32 = 10;

#[cortex_m_rt::entry]
fn main() -> ! {
    // cortex-m-rt turns a `static mut` declared here into a `&'static mut`
    // (the entry function runs once): the table lives in static memory,
    // not on the stack.
    static mut TABLE: Table = Table::new();
    let ok = run(TABLE);
    board::exit(ok)
}

fn run(table: &mut Table) -> bool {
    // α = 0.5, β = 0.2; gate from σ = 5 m, G = 13.8 (99.9 %), a_max = 5 m/s²;
    // targets up to 300 m/s.
    let config = match Gate::uncertainty(5.0, 13.8, 5.0)
        .map_err(|_| "gate")
        .and_then(|gate| {
            let gains = Gains::alpha_beta(0.5, 0.2).map_err(|_| "gains")?;
            TrackerConfig::new(gains, gate, 300.0).map_err(|_| "tracker configuration")
        }) {
        Ok(c) => c,
        Err(what) => {
            defmt::error!("static track table: invalid {=str}", what);
            return false;
        }
    };
    let mut codes = [Association::NotAssigned; 32];
    for k in 0..SCANS {
        let t = k as f32;
        let measurements = TARGETS.map(|([x, y], [vx, vy])| Measurement::Cartesian {
            x: x + vx * t,
            y: y + vy * t,
        });
        if let Err(e) = table.scan(&config, 1000 * k, &measurements, &mut codes) {
            defmt::error!("static track table: scan {=u32} refused: {}", k, e);
            return false;
        }
    }
    let t_end = (SCANS - 1) as f32;
    let mut confirmed = 0;
    for track in table.tracks() {
        let [x, y] = track.position();
        let near = TARGETS.iter().any(|([x0, y0], [vx, vy])| {
            libm::fabsf(x - (x0 + vx * t_end)) < 1.0 && libm::fabsf(y - (y0 + vy * t_end)) < 1.0
        });
        if track.status() != TrackStatus::Confirmed || !near {
            defmt::error!(
                "static track table: unexpected track at ({=f32}, {=f32}) m",
                x,
                y
            );
            return false;
        }
        confirmed += 1;
    }
    defmt::println!(
        "static track table: {=usize} confirmed tracks, all within 1 m ({=usize} bytes of static memory)",
        confirmed,
        core::mem::size_of::<Table>()
    );
    confirmed == TARGETS.len()
}
