//! `cargo xtask experiments` rejects bad options with a one-line reason. (The run itself is
//! checked by CI: `.ci/run` runs `--quick` in release and checks every file and header.)

mod common;

use common::xtask;

#[test]
fn tower_sizes_outside_one_to_a_thousand_are_rejected() {
    for (sizes, reason) in [
        ("0", "towers have 1 to 1000 cubes, got 0"),
        ("10,1001", "towers have 1 to 1000 cubes, got 1001"),
        ("ten", "`ten` is not a whole number of cubes"),
    ] {
        let out = xtask(&["experiments", "--sizes", sizes, "--out", "/nonexistent"]);
        assert!(!out.status.success(), "--sizes {sizes} was accepted");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(reason), "--sizes {sizes}: {stderr}");
    }
}

#[test]
fn an_output_folder_that_cannot_be_created_is_named() {
    let file = std::env::temp_dir().join(format!("tatami-not-a-folder-{}", std::process::id()));
    std::fs::write(&file, "").unwrap();
    let out_dir = file.join("experiments");
    let out = xtask(&["experiments", "--quick", "--out", out_dir.to_str().unwrap()]);
    std::fs::remove_file(&file).unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(stderr.contains(out_dir.to_str().unwrap()), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
}
