//! What the peer benchmarks share (`vs_mujoco`, `vs_pinocchio`).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository's root.
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("mbd-bench sits in the repository").to_path_buf()
}

/// The peers' pinned Python (MuJoCo, Pinocchio): runs `peers/ensure_env.sh`, which creates it
/// on first use and prints its interpreter.
pub fn peers_python() -> String {
    let peers = repo().join("mbd-bench/peers");
    let env = Command::new("bash").arg(peers.join("ensure_env.sh")).output().expect("bash runs peers/ensure_env.sh");
    assert!(env.status.success(), "peers/ensure_env.sh failed:\n{}", String::from_utf8_lossy(&env.stderr));
    let stdout = String::from_utf8_lossy(&env.stdout);
    stdout.lines().last().expect("ensure_env.sh prints the interpreter").trim().to_string()
}
