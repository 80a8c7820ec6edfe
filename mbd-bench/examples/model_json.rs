//! Writes the model JSON (`MODEL_JSON`) of the spatial benchmark mechanisms to a folder, for
//! `python -m mbd_oracle.codegen` (see `casadi/generate_spatial.sh`, which runs this):
//! `cargo run -p mbd-bench --example model_json -- DIR`.
use mbd::Mechanism;

mod spatial_slider_crank {
    include!("../mechanisms/spatial_slider_crank.rs");
}
mod free_spatial_slider_crank {
    include!("../mechanisms/free_spatial_slider_crank.rs");
}
mod spatial_chain16 {
    include!("../mechanisms/spatial_chain16.rs");
}

fn write<M: Mechanism>(dir: &std::path::Path, file: &str) {
    let path = dir.join(file);
    std::fs::write(&path, M::MODEL_JSON).unwrap_or_else(|e| panic!("write {}: {e}", path.display()));
    println!("{}: {}", M::NAME, path.display());
}

fn main() {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).expect("usage: model_json DIR"));
    std::fs::create_dir_all(&dir).expect("create the output folder");
    write::<spatial_slider_crank::SpatialSliderCrank>(&dir, "spatial_slider_crank.json");
    write::<free_spatial_slider_crank::FreeSpatialSliderCrank>(&dir, "free_spatial_slider_crank.json");
    write::<spatial_chain16::SpatialChain16>(&dir, "spatial_chain16.json");
}
