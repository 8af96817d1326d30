//! The host tools as a user runs them in a shell: a closed pipe
//! (`replay … | head`) ends a tool quietly with status 0 (before, replay
//! printed "cannot write the output: Broken pipe" and exited 1), and every
//! tool answers --help with status 0 and no internal issue number.

use std::io::Read;
use std::path::PathBuf;
use std::process::{Command, Stdio};

use abtrack_host_tests::scenario;

/// Runs `program args`, closing the read end of its stdout before it
/// writes anything: its first write fails with EPIPE. Returns the exit
/// code and stderr.
fn with_stdout_closed(program: &str, args: &[&str]) -> (Option<i32>, String) {
    let mut child = Command::new(program)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    drop(child.stdout.take());
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    (child.wait().unwrap().code(), err)
}

fn temp_file(name: &str, contents: &str) -> PathBuf {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("tools-cli-{}-{name}", std::process::id()));
    std::fs::write(&path, contents).unwrap();
    path
}

#[test]
fn a_closed_pipe_ends_each_tool_quietly_with_status_zero() {
    let csv = scenario::generate("two-crossing", 1)
        .unwrap()
        .measurements_csv();
    let path = temp_file("crossing.csv", &csv);
    let file = path.to_str().unwrap();
    let replay = env!("CARGO_BIN_EXE_replay");
    let (code, err) = with_stdout_closed(replay, &["--tracker", file]);
    assert_eq!(code, Some(0), "{err}");
    assert!(!err.contains("Broken pipe"), "{err}");
    // The tracker's report still goes to stderr.
    assert!(err.contains("measurements in 60 scans"), "{err}");
    let one = temp_file("one.csv", "t,x\n0,1\n1,2\n2,3\n");
    let (code, err) = with_stdout_closed(
        replay,
        &["--filter", "ab", "--schedule", "m2", one.to_str().unwrap()],
    );
    assert_eq!((code, err.as_str()), (Some(0), ""));
    let (code, err) = with_stdout_closed(env!("CARGO_BIN_EXE_simulate"), &["--list"]);
    assert_eq!((code, err.as_str()), (Some(0), ""));
    let _ = std::fs::remove_file(path);
    let _ = std::fs::remove_file(one);
}

#[test]
fn the_real_shell_pipe_into_head_exits_zero() {
    // Large enough (the dense scenario, about 300 kB of tracks) that replay
    // is still writing when head has gone.
    let csv = scenario::generate("dense", 1).unwrap().measurements_csv();
    let path = temp_file("dense.csv", &csv);
    let script = format!(
        "set -o pipefail; '{}' --tracker --numeric f32 '{}' | head -n 2",
        env!("CARGO_BIN_EXE_replay"),
        path.display()
    );
    let out = Command::new("bash").args(["-c", &script]).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "status {:?}: {err}", out.status);
    assert_eq!(String::from_utf8_lossy(&out.stdout).lines().count(), 2);
    assert!(!err.contains("Broken pipe"), "{err}");
    let _ = std::fs::remove_file(path);
}

#[test]
fn every_tool_has_help_without_issue_numbers() {
    for program in [
        env!("CARGO_BIN_EXE_replay"),
        env!("CARGO_BIN_EXE_simulate"),
        env!("CARGO_BIN_EXE_experiments"),
        env!("CARGO_BIN_EXE_precision"),
        env!("CARGO_BIN_EXE_frames"),
        env!("CARGO_BIN_EXE_bench_report"),
        env!("CARGO_BIN_EXE_firmware-check"),
    ] {
        let out = Command::new(program).arg("--help").output().unwrap();
        assert!(out.status.success(), "{program}");
        let help = String::from_utf8_lossy(&out.stdout);
        assert!(help.contains("Usage:"), "{program}: {help}");
        assert!(
            !help.to_lowercase().contains("issue"),
            "{program} --help names an issue:\n{help}"
        );
    }
    // A bad argument is a usage error (status 2) for each.
    for (program, arg) in [
        (env!("CARGO_BIN_EXE_experiments"), "--only=nope"),
        (env!("CARGO_BIN_EXE_experiments"), "--runs=1"),
        (env!("CARGO_BIN_EXE_precision"), "--frobnicate"),
        (env!("CARGO_BIN_EXE_frames"), "--frobnicate"),
        (env!("CARGO_BIN_EXE_bench_report"), "--frobnicate"),
        (env!("CARGO_BIN_EXE_firmware-check"), "--frobnicate"),
    ] {
        let out = Command::new(program).arg(arg).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{program} {arg}");
    }
}
