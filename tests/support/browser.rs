//! Pages opened in headless Chromium (WebGL on SwiftShader), what the
//! animation tests share: finding Chromium (or saying the test skipped),
//! the DOM dumped once the page's virtual time has run out, the JSON a
//! probe script wrote into `<pre id="probe">` with every number as its
//! shortest round-trip string, several pages probed in one launch
//! ([`probe_pages`]), and the screenshots the guide shows ([`screenshot`]).
//!
//! Chromium (Debian's `chromium`) runs the pages where it is on `PATH`;
//! without it a test says it skipped, and fails where
//! `CHAPLYGIN_BROWSER_TESTS=require` (as `.ci/run` sets it, after
//! installing Chromium when missing).

use serde_json::Value;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Chromium's path; `None` after saying the test skipped, where it is not
/// on `PATH` and not required.
pub fn chromium() -> Option<PathBuf> {
    super::tool(
        "chromium",
        "CHAPLYGIN_BROWSER_TESTS",
        "`apt-get install -y chromium` on Debian",
    )
}

/// What every probe script does first: it records console errors, page
/// errors, failed loads, unhandled rejections and blocked requests in
/// `errors`.
const PROBE_START: &str = r#"<script>
(() => {
  const errors = [];
  const original = console.error.bind(console);
  console.error = (...args) => { errors.push('console.error: ' + args.map(String).join(' ')); original(...args); };
  window.addEventListener('error', (event) => {
    if (event.target && event.target !== window) errors.push('failed load: ' + (event.target.src || event.target.href || event.target.tagName));
    else errors.push('error: ' + event.message);
  }, true);
  window.addEventListener('unhandledrejection', (event) => errors.push('unhandled rejection: ' + event.reason));
  document.addEventListener('securitypolicyviolation', (event) => errors.push('blocked: ' + event.blockedURI + ' (' + event.violatedDirective + ')'));
"#;

/// What every probe script does last: once the page has loaded, it runs the
/// test's `measure()` and writes its result (numbers as strings, `-0` kept)
/// as JSON into `<pre id="probe">`, for [`probe_result`].
const PROBE_END: &str = r#"
  window.addEventListener('load', () => {
    measure().catch((error) => ({ errors: errors.concat(['probe: ' + error]) })).then((result) => {
      const pre = document.createElement('pre');
      pre.id = 'probe';
      pre.textContent = JSON.stringify(result, (key, value) => (typeof value !== 'number' ? value : Object.is(value, -0) ? '-0' : String(value)));
      document.body.appendChild(pre);
    });
  });
})();
</script>
"#;

/// `html` with a probe script first in its `<head>`: [`PROBE_START`], the
/// test's `measure` (an `async function measure()` returning the result,
/// which may read `errors`), [`PROBE_END`].
pub fn probed(html: &str, measure: &str) -> String {
    let probe = format!("{PROBE_START}\n{measure}{PROBE_END}");
    let probed = html.replacen("<head>", &format!("<head>\n{probe}"), 1);
    assert_ne!(probed, html, "the page has a <head>");
    probed
}

/// The harness's script: once every frame's probe has written its
/// result, their JSON texts as one array in the harness's own
/// `<pre id="probe">`.
const HARNESS: &str = r#"<script>
(() => {
  function collect() {
    const found = Array.from(document.querySelectorAll('iframe'), (frame) => {
      const probe = frame.contentDocument && frame.contentDocument.getElementById('probe');
      return probe ? probe.textContent : null;
    });
    if (found.some((text) => text === null)) return setTimeout(collect, 50);
    const pre = document.createElement('pre');
    pre.id = 'probe';
    pre.textContent = '[' + found.join(',') + ']';
    document.body.appendChild(pre);
  }
  window.addEventListener('load', collect);
})();
</script>
"#;

/// `pages` opened together in one headless Chromium, each in an
/// `<iframe srcdoc>` of 480 x 320 pixels of a harness page (which shares
/// the frames' origin) written in `directory`, each probed with `measure`
/// as [`probed`] does: the probes' results in the order of `pages`.
pub fn probe_pages(chromium: &Path, pages: &[&str], measure: &str, directory: &Path) -> Vec<Value> {
    let mut harness =
        String::from("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"></head><body>\n");
    for page in pages {
        let escaped = probed(page, measure)
            .replace('&', "&amp;")
            .replace('"', "&quot;");
        writeln!(
            harness,
            "<iframe width=\"480\" height=\"320\" srcdoc=\"{escaped}\"></iframe>"
        )
        .expect("writing to a String");
    }
    harness.push_str(HARNESS);
    harness.push_str("</body></html>\n");
    let path = directory.join("harness.html");
    std::fs::write(&path, harness).unwrap();
    let result = probe_result(&dump_dom(chromium, &path, &directory.join("profile")));
    let results = result.as_array().expect("one result per page").clone();
    assert_eq!(results.len(), pages.len());
    results
}

/// The width and height of the guide's screenshots, pixels.
pub const SCREENSHOT_SIZE: (u32, u32) = (960, 540);

/// The guide's screenshot `docs/guide/images/{name}.png` of `page` at time
/// `t`, the camera following the items: taken by headless Chromium where
/// `CHAPLYGIN_SCREENSHOTS=write` (docs/guide/contributing.md), and otherwise
/// checked to be there, a PNG of [`SCREENSHOT_SIZE`].
pub fn screenshot(page: &str, t: f64, name: &str, directory: &Path) {
    let path = super::markdown::root().join(format!("docs/guide/images/{name}.png"));
    if std::env::var("CHAPLYGIN_SCREENSHOTS").as_deref() == Ok("write")
        && let Some(chromium) = chromium()
    {
        let script = format!(
            "<script>window.addEventListener('load', () => window.chaplygin.ready.then(() => {{ \
             document.getElementById('follow').checked = true; window.chaplygin.seek({t}); }}));</script>"
        );
        let copy = directory.join(format!("{name}.html"));
        std::fs::write(
            &copy,
            page.replacen("</body>", &format!("{script}</body>"), 1),
        )
        .unwrap();
        let (width, height) = SCREENSHOT_SIZE;
        let status = Command::new(chromium)
            .args(HEADLESS)
            .arg(format!("--window-size={width},{height}"))
            .arg("--hide-scrollbars")
            .arg(format!(
                "--user-data-dir={}",
                directory.join("profile").display()
            ))
            .arg(format!("--screenshot={}", path.display()))
            .arg(format!("file://{}", copy.display()))
            .stderr(Stdio::null())
            .status()
            .expect("chromium starts");
        assert!(status.success(), "chromium's screenshot: {status}");
        eprintln!("wrote {}", path.display());
    }
    let bytes = std::fs::read(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e}; take it with CHAPLYGIN_SCREENSHOTS=write (docs/guide/contributing.md)",
            path.display()
        )
    });
    assert!(
        bytes.starts_with(b"\x89PNG\r\n\x1a\n") && &bytes[12..16] == b"IHDR",
        "{} is a PNG",
        path.display()
    );
    let number = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
    assert_eq!(
        (number(16), number(20)),
        SCREENSHOT_SIZE,
        "{}",
        path.display()
    );
}

/// How Chromium runs the pages: headless, WebGL on SwiftShader, the page's
/// time virtual.
const HEADLESS: [&str; 6] = [
    "--headless=new",
    "--no-sandbox",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--virtual-time-budget=20000",
    "--no-first-run",
];

/// `page` opened in headless Chromium (WebGL on SwiftShader), its DOM once
/// the virtual time budget has run out.
pub fn dump_dom(chromium: &Path, page: &Path, profile: &Path) -> String {
    let started = Instant::now();
    let mut child = Command::new(chromium)
        .args(HEADLESS)
        .arg("--window-size=960,640")
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg("--dump-dom")
        .arg(format!("file://{}", page.display()))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("chromium starts");
    let reader = {
        let mut stdout = child.stdout.take().unwrap();
        std::thread::spawn(move || {
            let mut text = String::new();
            std::io::Read::read_to_string(&mut stdout, &mut text).unwrap();
            text
        })
    };
    let errors = {
        let mut stderr = child.stderr.take().unwrap();
        std::thread::spawn(move || {
            let mut text = String::new();
            let _ = std::io::Read::read_to_string(&mut stderr, &mut text);
            text
        })
    };
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() > Duration::from_secs(180) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("chromium ran for over 180 s: {}", errors.join().unwrap());
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let dom = reader.join().unwrap();
    let errors = errors.join().unwrap();
    assert!(status.success(), "chromium failed ({status}): {errors}");
    eprintln!("chromium: {:.1} s", started.elapsed().as_secs_f64());
    dom
}

/// The probe's findings in the dumped DOM.
pub fn probe_result(dom: &str) -> Value {
    let start = dom
        .find("<pre id=\"probe\">")
        .unwrap_or_else(|| panic!("the probe wrote no result; the DOM:\n{dom}"))
        + "<pre id=\"probe\">".len();
    let end = start + dom[start..].find("</pre>").unwrap();
    let text = dom[start..end]
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&amp;", "&");
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("the probe's JSON: {e}\n{text}"))
}

/// A number the probe wrote as its shortest round-trip string.
pub fn num(value: &Value) -> f64 {
    value
        .as_str()
        .unwrap_or_else(|| panic!("a number as a string: {value}"))
        .parse()
        .unwrap()
}

/// An array of numbers the probe wrote as strings.
pub fn nums(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap_or_else(|| panic!("an array: {value}"))
        .iter()
        .map(num)
        .collect()
}

/// A pose the probe read: position and quaternion.
pub fn pose_of(value: &Value) -> ([f64; 3], [f64; 4]) {
    (
        nums(&value["position"]).try_into().unwrap(),
        nums(&value["quaternion"]).try_into().unwrap(),
    )
}

/// The Euclidean distance between two points.
pub fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}
