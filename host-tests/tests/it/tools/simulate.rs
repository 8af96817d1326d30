//! The `simulate` binary as a user runs it: exit codes and messages.

use std::process::Command;

fn simulate(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_simulate"))
        .args(args)
        .output()
        .expect("run simulate")
}

#[test]
fn writes_both_files_and_exits_zero() {
    let dir = std::env::temp_dir().join(format!("abtrack-simulate-cli-{}", std::process::id()));
    let out = simulate(&[
        "--scenario",
        "he-tcas",
        "--seed",
        "5",
        "--out-dir",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let m = std::fs::read_to_string(dir.join("measurements.csv")).unwrap();
    let t = std::fs::read_to_string(dir.join("truth.csv")).unwrap();
    assert_eq!(m.lines().count(), 501);
    assert_eq!(t.lines().count(), 501);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn usage_errors_exit_two_with_a_message() {
    let out = simulate(&["--scenario", "no-such", "--out-dir", "/tmp/x"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("error: invalid value 'no-such' for '--scenario <NAME>'"),
        "{err}"
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn list_exits_zero() {
    let out = simulate(&["--list"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("tcas-converging"));
}
