//! Pages opened in headless Chromium (WebGL on SwiftShader), what the
//! animation tests share: finding Chromium (or saying the test skipped),
//! a scratch directory, the DOM dumped once the page's virtual time has
//! run out, and the JSON a probe script wrote into `<pre id="probe">`
//! with every number as its shortest round-trip string.
//!
//! Chromium (Debian's `chromium`) runs the pages where it is on `PATH`;
//! without it a test says it skipped, and fails where
//! `CHAPLYGIN_BROWSER_TESTS=require` (as `.ci/run` sets it, after
//! installing Chromium when missing).

use serde_json::Value;
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

/// `page` opened in headless Chromium (WebGL on SwiftShader), its DOM once
/// the virtual time budget has run out.
pub fn dump_dom(chromium: &Path, page: &Path, profile: &Path) -> String {
    let started = Instant::now();
    let mut child = Command::new(chromium)
        .args([
            "--headless=new",
            "--no-sandbox",
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            "--virtual-time-budget=20000",
            "--window-size=960,640",
            "--no-first-run",
        ])
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
