//! The page of `cargo xtask view` in a real browser: headless Chromium (Debian's `chromium`)
//! opens it from disk, with the network off, and must find it ready, with the frame and body
//! counts of the contract, seekable through the URL, and drawing something (a screenshot that is
//! not one flat colour).
//!
//! Without a Chromium (`$CHROMIUM`, or `chromium`, `chromium-browser`, `google-chrome` on the
//! path) the test says so and passes — unless `CI` is set: `.ci/run` installs Chromium and the
//! test must run there.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn chromium() -> Option<PathBuf> {
    if let Some(path) = std::env::var_os("CHROMIUM") {
        return Some(PathBuf::from(path));
    }
    let names = ["chromium", "chromium-browser", "google-chrome"];
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|folder| names.iter().map(move |name| folder.join(name)))
        .find(|candidate| candidate.is_file())
}

/// Runs Chromium headless on `url` with `extra` arguments, killed after two minutes; returns its
/// standard output (through a file: the page, dumped, is larger than a pipe holds).
fn run_chromium(browser: &Path, profile: &Path, url: &str, extra: &[&str]) -> String {
    let output = profile.with_extension("out");
    let mut child = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            // WebGL in software: SwiftShader, which recent Chromium only uses when told to.
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--no-first-run",
            "--hide-scrollbars",
            "--window-size=800,600",
            "--virtual-time-budget=10000",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(extra)
        .arg(url)
        .stdout(std::fs::File::create(&output).unwrap())
        .stderr(Stdio::null())
        .spawn()
        .expect("Chromium starts");
    let deadline = Instant::now() + Duration::from_secs(120);
    while child.try_wait().unwrap().is_none() {
        if Instant::now() > deadline {
            child.kill().unwrap();
            panic!("Chromium did not finish in 2 minutes");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    String::from_utf8_lossy(&std::fs::read(&output).unwrap()).into_owned()
}

/// The value of attribute `name` in the `<body>` tag of `dom`.
fn body_attribute<'a>(dom: &'a str, name: &str) -> Option<&'a str> {
    let start = dom.find("<body")?;
    let tag = &dom[start..start + dom[start..].find('>')?];
    let key = format!("{name}=\"");
    let from = tag.find(&key)? + key.len();
    Some(&tag[from..from + tag[from..].find('"')?])
}

#[test]
fn the_page_loads_seeks_and_draws_in_headless_chromium() {
    let Some(browser) = chromium() else {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI must run the browser test: install Chromium (apt-get install -y chromium)"
        );
        eprintln!("no Chromium found: the browser test did not run");
        return;
    };
    let folder = std::env::temp_dir().join(format!("tatami-browser-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    let page = folder.join("offset_pair.html");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/offset_pair.json");
    let status = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .arg("view")
        .arg(&scene)
        .args(["--steps", "100", "--out"])
        .arg(&page)
        .status()
        .unwrap();
    assert!(status.success());
    let url = format!("file://{}", page.display());
    let profile = folder.join("profile");

    // Steps 0, 2, …, 100 at dt 0.01 (60 frames per simulated second at most); three bodies.
    let dom = run_chromium(&browser, &profile, &format!("{url}#t=0.5"), &["--dump-dom"]);
    assert_eq!(
        body_attribute(&dom, "data-error"),
        None,
        "the page failed to draw"
    );
    assert_eq!(
        body_attribute(&dom, "data-ready"),
        Some("true"),
        "{dom:.300}"
    );
    assert_eq!(body_attribute(&dom, "data-frames"), Some("51"));
    assert_eq!(body_attribute(&dom, "data-bodies"), Some("3"));
    assert_eq!(body_attribute(&dom, "data-step"), Some("50"), "seek(0.5)");

    let screenshot = folder.join("shot.png");
    run_chromium(
        &browser,
        &profile,
        &url,
        &[&format!("--screenshot={}", screenshot.display())],
    );
    let decoder = png::Decoder::new(std::fs::File::open(&screenshot).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut pixels).unwrap();
    let channels = info.color_type.samples();
    let colours: std::collections::HashSet<&[u8]> =
        pixels[..info.buffer_size()].chunks(channels).collect();
    // A blank or failed canvas is one or two colours; shaded boxes, a grid and the overlay give
    // thousands.
    assert!(colours.len() > 500, "{} colours", colours.len());
    std::fs::remove_dir_all(&folder).unwrap();
}
