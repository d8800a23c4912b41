//! End-to-end tests of `radc lsp`: the real binary driven over stdio with JSON-RPC, as
//! an editor drives it. Every response is checked exactly.

use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

use serde_json::{Value, json};

const TIMEOUT: Duration = Duration::from_secs(20);

/// A minimal LSP client: frames messages, correlates responses by id, keeps
/// notifications until asked for, and answers requests from the server with `null`.
struct Client {
    child: Child,
    stdin: ChildStdin,
    incoming: Receiver<Value>,
    unread: Vec<Value>,
    next_id: i64,
}

impl Client {
    fn start() -> Client {
        Client::start_with_env(&[])
    }

    fn start_with_env(vars: &[(&str, &str)]) -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_radc"))
            .arg("lsp")
            .envs(vars.iter().copied())
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("radc lsp starts");
        let stdin = child.stdin.take().expect("stdin");
        let stdout = child.stdout.take().expect("stdout");
        let (tx, incoming) = channel();
        std::thread::spawn(move || {
            let mut reader = BufReader::new(stdout);
            while let Some(message) = read_message(&mut reader) {
                if tx.send(message).is_err() {
                    break;
                }
            }
        });
        Client {
            child,
            stdin,
            incoming,
            unread: Vec::new(),
            next_id: 1,
        }
    }

    fn send(&mut self, message: &Value) {
        let body = message.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).expect("write");
        self.stdin.flush().expect("flush");
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(&json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    fn receive(&mut self) -> Value {
        let message = self
            .incoming
            .recv_timeout(TIMEOUT)
            .expect("the server answers in time");
        if let (Some(id), Some(_)) = (message.get("id"), message.get("method")) {
            let reply = json!({"jsonrpc": "2.0", "id": id, "result": null});
            self.send(&reply);
        }
        message
    }

    /// Sends a request and returns its `result` (panicking on an error response).
    fn request(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        self.send(&json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        loop {
            let message = self.receive();
            if message.get("id") == Some(&json!(id)) && message.get("method").is_none() {
                assert!(message.get("error").is_none(), "{method}: {message}");
                return message.get("result").cloned().unwrap_or(Value::Null);
            }
            self.unread.push(message);
        }
    }

    /// The params of the next notification called `method`.
    fn notification(&mut self, method: &str) -> Value {
        if let Some(i) = self.unread.iter().position(|m| m["method"] == method) {
            return self.unread.remove(i)["params"].take();
        }
        loop {
            let message = self.receive();
            if message["method"] == method {
                return message["params"].clone();
            }
            self.unread.push(message);
        }
    }

    fn shutdown(mut self) {
        assert_eq!(self.request("shutdown", Value::Null), Value::Null);
        self.notify("exit", Value::Null);
        for _ in 0..200 {
            if let Ok(Some(status)) = self.child.try_wait() {
                assert!(status.success(), "exit status {status}");
                return;
            }
            std::thread::sleep(Duration::from_millis(25));
        }
        let _ = self.child.kill();
        panic!("the server did not exit after 'exit'");
    }
}

fn read_message(reader: &mut impl BufRead) -> Option<Value> {
    let mut length = None;
    loop {
        let mut line = String::new();
        if reader.read_line(&mut line).ok()? == 0 {
            return None;
        }
        let line = line.trim_end();
        if line.is_empty() {
            break;
        }
        if let Some(n) = line.strip_prefix("Content-Length: ") {
            length = n.parse::<usize>().ok();
        }
    }
    let mut body = vec![0; length?];
    reader.read_exact(&mut body).ok()?;
    serde_json::from_slice(&body).ok()
}

/// The LSP position of the `nth` occurrence of `needle` in `text`, plus `shift` columns.
fn pos(text: &str, needle: &str, nth: usize, shift: u32) -> Value {
    let offset = text
        .match_indices(needle)
        .nth(nth)
        .map(|(i, _)| i)
        .expect("needle in text");
    let line = text[..offset].matches('\n').count();
    let column = offset - text[..offset].rfind('\n').map_or(0, |i| i + 1);
    json!({"line": line, "character": column as u32 + shift})
}

fn range(l0: u32, c0: u32, l1: u32, c1: u32) -> Value {
    json!({"start": {"line": l0, "character": c0}, "end": {"line": l1, "character": c1}})
}

/// A scene with one error: the sphere has three reals, not four.
const BROKEN: &str =
    "void plastic red\n0\n0\n5 .5 .1 .1 .05 .1\n\nred sphere ball\n0\n0\n3 0 0 0\n";

/// The same scene fixed, laid out untidily.
const UNTIDY: &str =
    "void plastic red\n0\n0\n5 .5 .1 .1 .05 .1\n\n\n\nred   sphere ball 0 0\n4 0 0 0 1\n";

const TIDY: &str =
    "void plastic red\n0\n0\n5 .5 .1 .1 .05 .1\n\nred sphere ball\n0\n0\n4 0 0 0 1\n";

struct Workspace {
    _dir: tempfile::TempDir,
    path: std::path::PathBuf,
    uri: String,
}

fn workspace() -> Workspace {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("scene.rad");
    let uri = file_uri(&path);
    Workspace {
        _dir: dir,
        path,
        uri,
    }
}

fn initialize(client: &mut Client, options: Value) -> Value {
    initialize_with(client, options, json!({}))
}

fn initialize_with(client: &mut Client, options: Value, capabilities: Value) -> Value {
    let result = client.request(
        "initialize",
        json!({"processId": null, "rootUri": null, "capabilities": capabilities, "initializationOptions": options}),
    );
    client.notify("initialized", json!({}));
    result
}

fn open(client: &mut Client, uri: &str, text: &str) {
    client.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "radiance", "version": 1, "text": text}}),
    );
}

fn change(client: &mut Client, uri: &str, version: i32, text: &str) {
    client.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": uri, "version": version}, "contentChanges": [{"text": text}]}),
    );
}

fn at(uri: &str, position: Value) -> Value {
    json!({"textDocument": {"uri": uri}, "position": position})
}

#[test]
fn a_session_from_initialize_to_exit() {
    let ws = workspace();
    let uri = ws.uri.as_str();
    let mut client = Client::start();

    let init = initialize(&mut client, json!({"inlayHints": {"enabled": true}}));
    assert_eq!(init["serverInfo"]["name"], "radc");
    let caps = &init["capabilities"];
    assert_eq!(caps["textDocumentSync"]["change"], 2);
    for provider in [
        "hoverProvider",
        "definitionProvider",
        "referencesProvider",
        "documentSymbolProvider",
        "inlayHintProvider",
        "documentFormattingProvider",
        "colorProvider",
    ] {
        assert_eq!(caps[provider], true, "{provider}");
    }

    // didOpen: the same diagnostic `radc check` gives, word for word.
    open(&mut client, uri, BROKEN);
    let published = client.notification("textDocument/publishDiagnostics");
    assert_eq!(
        published,
        json!({
            "uri": uri,
            "version": 1,
            "diagnostics": [{
                "range": range(8, 0, 8, 1),
                "severity": 1,
                "code": "E0202",
                "source": "radc",
                "message": "sphere takes 4 real arguments, found 3",
                "relatedInformation": [
                    {"location": {"uri": uri, "range": range(5, 4, 5, 10)}, "message": "surface sphere"},
                    {
                        "location": {"uri": uri, "range": range(8, 0, 8, 1)},
                        "message": "hint: sphere real arguments: xc yc zc radius"
                    }
                ]
            }]
        })
    );
    std::fs::write(&ws.path, BROKEN).expect("write scene");
    let cli = Command::new(env!("CARGO_BIN_EXE_radc"))
        .args(["check", "--format", "json"])
        .arg(&ws.path)
        .output()
        .expect("radc check runs");
    let cli: Vec<Value> = String::from_utf8_lossy(&cli.stdout)
        .lines()
        .filter_map(|l| serde_json::from_str(l).ok())
        .collect();
    assert_eq!(cli.len(), 1);
    let lsp = &published["diagnostics"][0];
    assert_eq!(cli[0]["code"], lsp["code"]);
    assert_eq!(cli[0]["message"], lsp["message"]);
    assert_eq!(
        cli[0]["line"],
        json!(lsp["range"]["start"]["line"].as_u64().map(|l| l + 1))
    );

    // didChange: fixed, diagnostics cleared for version 2.
    change(&mut client, uri, 2, UNTIDY);
    let published = client.notification("textDocument/publishDiagnostics");
    assert_eq!(
        published,
        json!({"uri": uri, "version": 2, "diagnostics": []})
    );

    // Hover on a type keyword: its documentation and layout from the schema.
    let hover = client.request("textDocument/hover", at(uri, pos(UNTIDY, "plastic", 0, 2)));
    let plastic = radc_lang::schema::lookup("plastic").expect("plastic");
    assert_eq!(hover["contents"]["kind"], "markdown");
    assert_eq!(
        hover["contents"]["value"],
        radc_lang::schema::hover(plastic)
    );
    assert_eq!(hover["range"], range(0, 5, 0, 12));

    // Hover on an argument: its name and meaning.
    let hover = client.request("textDocument/hover", at(uri, pos(UNTIDY, ".05", 0, 1)));
    let text = hover["contents"]["value"].as_str().unwrap_or_default();
    assert!(text.starts_with("spec — specularity"), "{text}");
    let hint = radc_lang::schema::arg_hint(plastic, radc_lang::schema::ArgSide::Reals, 3);
    assert_eq!(
        text,
        format!(
            "{}\n\nreal argument 4 of **plastic**",
            hint.unwrap_or_default()
        )
    );
    assert_eq!(hover["range"], range(3, 11, 3, 14));

    // Hover on a modifier: its definition.
    let hover = client.request("textDocument/hover", at(uri, pos(UNTIDY, "red ", 0, 1)));
    assert_eq!(
        hover["contents"]["value"],
        "**red** — plastic (material), defined on line 1\n\n```radiance\nvoid plastic red\n0\n0\n5 .5 .1 .1 .05 .1\n```"
    );
    let hover = client.request(
        "textDocument/hover",
        at(uri, pos(UNTIDY, "red   sphere", 0, 0)),
    );
    assert_eq!(hover["range"], range(7, 0, 7, 3));

    // Go to definition and find references.
    let definition = client.request(
        "textDocument/definition",
        at(uri, pos(UNTIDY, "red   sphere", 0, 1)),
    );
    assert_eq!(
        definition,
        json!({"uri": uri, "range": range(0, 13, 0, 16)})
    );
    let mut params = at(uri, pos(UNTIDY, "plastic red", 0, 9));
    params["context"] = json!({"includeDeclaration": true});
    let references = client.request("textDocument/references", params);
    assert_eq!(
        references,
        json!([{"uri": uri, "range": range(0, 13, 0, 16)}, {"uri": uri, "range": range(7, 0, 7, 3)}])
    );

    // Rename rewrites the definition and the uses bound to it.
    let mut params = at(uri, pos(UNTIDY, "red   sphere", 0, 1));
    params["newName"] = json!("paint");
    let rename = client.request("textDocument/rename", params);
    assert_eq!(
        rename,
        json!({"changes": {uri: [
            {"range": range(0, 13, 0, 16), "newText": "paint"},
            {"range": range(7, 0, 7, 3), "newText": "paint"}
        ]}})
    );

    // Inlay hints name the reals.
    let hints = client.request(
        "textDocument/inlayHint",
        json!({"textDocument": {"uri": uri}, "range": range(0, 0, 9, 0)}),
    );
    let labels: Vec<&str> = hints
        .as_array()
        .map(|a| a.iter().filter_map(|h| h["label"].as_str()).collect())
        .unwrap_or_default();
    assert_eq!(
        labels,
        [
            "red=", "green=", "blue=", "spec=", "rough=", "xc=", "yc=", "zc=", "radius="
        ]
    );
    assert_eq!(
        hints[3],
        json!({"position": {"line": 3, "character": 11}, "label": "spec=", "kind": 2})
    );

    // Outline and colours.
    let symbols = client.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": uri}}),
    );
    let outline: Vec<(String, String)> = symbols
        .as_array()
        .map(|a| {
            a.iter()
                .map(|s| (s["name"].to_string(), s["detail"].to_string()))
                .collect()
        })
        .unwrap_or_default();
    assert_eq!(
        outline,
        [
            ("\"red\"".to_string(), "\"plastic\"".to_string()),
            ("\"ball\"".to_string(), "\"sphere\"".to_string())
        ]
    );
    let colors = client.request(
        "textDocument/documentColor",
        json!({"textDocument": {"uri": uri}}),
    );
    // Colours travel as f32.
    let tenth = f64::from(0.1f32);
    assert_eq!(
        colors,
        json!([{"range": range(3, 2, 3, 10), "color": {"red": 0.5, "green": tenth, "blue": tenth, "alpha": 1.0}}])
    );
    let presentations = client.request(
        "textDocument/colorPresentation",
        json!({"textDocument": {"uri": uri}, "range": range(3, 2, 3, 10),
               "color": {"red": 0.25, "green": 0.5, "blue": 1.0, "alpha": 1.0}}),
    );
    assert_eq!(
        presentations,
        json!([{"label": "0.25 0.5 1", "textEdit": {"range": range(3, 2, 3, 10), "newText": "0.25 0.5 1"}}])
    );

    // Formatting: one edit to the conventional layout; formatting that again is a no-op.
    let options = json!({"tabSize": 4, "insertSpaces": true});
    let edits = client.request(
        "textDocument/formatting",
        json!({"textDocument": {"uri": uri}, "options": options}),
    );
    assert_eq!(
        edits,
        json!([{"range": range(0, 0, 9, 0), "newText": TIDY}])
    );
    change(&mut client, uri, 3, TIDY);
    client.notification("textDocument/publishDiagnostics");
    let edits = client.request(
        "textDocument/formatting",
        json!({"textDocument": {"uri": uri}, "options": options}),
    );
    assert_eq!(edits, json!([]));

    // Completion: modifiers in scope at the start of a line, types after a modifier.
    let typing = format!("{TIDY}\nred ");
    change(&mut client, uri, 4, &typing);
    client.notification("textDocument/publishDiagnostics");
    let types = client.request(
        "textDocument/completion",
        at(uri, json!({"line": 10, "character": 4})),
    );
    let items = types.as_array().cloned().unwrap_or_default();
    assert_eq!(items.len(), radc_lang::schema::PRIMITIVE_TYPES.len());
    let plastic_item = items
        .iter()
        .find(|i| i["label"] == "plastic")
        .cloned()
        .unwrap_or_default();
    assert_eq!(plastic_item["insertTextFormat"], 2);
    assert_eq!(
        plastic_item["textEdit"],
        json!({
            "range": range(10, 4, 10, 4),
            "newText": "plastic ${2:name}\n0\n0\n5 ${3:red} ${4:green} ${5:blue} ${6:spec} ${7:rough}"
        })
    );
    let modifiers = client.request(
        "textDocument/completion",
        at(uri, json!({"line": 10, "character": 1})),
    );
    let labels: Vec<&str> = modifiers
        .as_array()
        .map(|a| a.iter().filter_map(|i| i["label"].as_str()).collect())
        .unwrap_or_default();
    assert_eq!(labels, ["void", "red"]);
    assert_eq!(modifiers[1]["textEdit"]["range"], range(10, 0, 10, 1));

    client.shutdown();
}

#[test]
fn inlay_hints_follow_the_setting() {
    let ws = workspace();
    let uri = ws.uri.as_str();
    let mut client = Client::start();
    let refresh = json!({"workspace": {"inlayHint": {"refreshSupport": true}}});
    initialize_with(
        &mut client,
        json!({"inlayHints": {"enabled": false}}),
        refresh,
    );
    open(&mut client, uri, TIDY);
    client.notification("textDocument/publishDiagnostics");
    let params = json!({"textDocument": {"uri": uri}, "range": range(0, 0, 9, 0)});
    assert_eq!(
        client.request("textDocument/inlayHint", params.clone()),
        Value::Null
    );
    client.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"radc": {"inlayHints": {"enabled": true}}}}),
    );
    client.notification("textDocument/publishDiagnostics");
    // The client asked to be told to refresh its hints (a request, answered by the harness).
    assert_eq!(
        client.notification("workspace/inlayHint/refresh"),
        Value::Null
    );
    let hints = client.request("textDocument/inlayHint", params);
    assert_eq!(hints.as_array().map(Vec::len), Some(9));
    client.shutdown();
}

#[test]
fn never_runs_commands_and_survives_nonsense() {
    let ws = workspace();
    let uri = ws.uri.as_str();
    let marker = ws.path.with_file_name("ran");
    let mut client = Client::start();
    initialize(&mut client, json!(null));
    let text = format!(
        "!touch {}\nvoid plastic\0 \"x\n5 1e999 -- \u{1F600}\n",
        marker.display()
    );
    open(&mut client, uri, &text);
    let published = client.notification("textDocument/publishDiagnostics");
    let codes: Vec<&str> = published["diagnostics"]
        .as_array()
        .map(|a| a.iter().filter_map(|d| d["code"].as_str()).collect())
        .unwrap_or_default();
    assert!(codes.contains(&"W0303"), "{codes:?}");
    assert!(!marker.exists(), "the server ran a '!' command");

    // A body that is not JSON is dropped; the server keeps serving.
    client
        .stdin
        .write_all(b"Content-Length: 7\r\n\r\n{hello}")
        .expect("write");

    // Positions past the end, documents never opened, formatting a broken file.
    for (method, params) in [
        (
            "textDocument/hover",
            at(uri, json!({"line": 99, "character": 99})),
        ),
        (
            "textDocument/definition",
            at(uri, json!({"line": 1, "character": 999})),
        ),
        (
            "textDocument/completion",
            at(uri, json!({"line": 2, "character": 3})),
        ),
        (
            "textDocument/hover",
            at(
                "file:///never/opened.rad",
                json!({"line": 0, "character": 0}),
            ),
        ),
        (
            "textDocument/formatting",
            json!({"textDocument": {"uri": uri}, "options": {"tabSize": 2, "insertSpaces": true}}),
        ),
    ] {
        let result = client.request(method, params);
        assert!(
            result.is_null() || result.is_array() || result.is_object(),
            "{method}: {result}"
        );
    }
    assert_eq!(
        client.request(
            "textDocument/formatting",
            json!({"textDocument": {"uri": uri}, "options": {"tabSize": 2, "insertSpaces": true}})
        ),
        Value::Null
    );
    client.shutdown();
}

/// [`codes`] without W0307: the tests of function files use patterns, which the
/// renderer does not run yet; what they test is what the checker finds.
fn checked_codes(published: &Value) -> Vec<String> {
    let mut c = codes(published);
    c.retain(|c| c != "W0307");
    c
}

fn codes(published: &Value) -> Vec<String> {
    published["diagnostics"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|d| d["code"].as_str().map(String::from))
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn saves_and_raypath_settings_recheck_auxiliary_files() {
    let ws = workspace();
    let uri = ws.uri.as_str();
    let dir = ws.path.parent().expect("scene folder").to_path_buf();
    let scene = |cal: &str| {
        format!("void brightfunc b\n2 refl {cal}\n0\n0\n\nb sphere s\n0\n0\n4 0 0 0 1\n")
    };
    let mut client = Client::start();
    initialize(&mut client, json!({"raypath": []}));

    open(&mut client, uri, &scene("funcs.cal"));
    let published = client.notification("textDocument/publishDiagnostics");
    assert_eq!(checked_codes(&published), ["E0305"]);
    assert_eq!(
        published["diagnostics"][0]["message"],
        "file 'funcs.cal' not found"
    );

    // The file appears next to the scene; a save re-checks (without an edit).
    std::fs::write(dir.join("funcs.cal"), "refl = 1;\n").expect("write cal");
    client.notify(
        "textDocument/didSave",
        json!({"textDocument": {"uri": uri}}),
    );
    assert_eq!(
        checked_codes(&client.notification("textDocument/publishDiagnostics")),
        Vec::<String>::new()
    );

    // A file found only along the configured RAYPATH.
    let lib = dir.join("lib");
    std::fs::create_dir(&lib).expect("lib folder");
    std::fs::write(lib.join("other.cal"), "refl = 1;\n").expect("write cal");
    change(&mut client, uri, 2, &scene("other.cal"));
    assert_eq!(
        checked_codes(&client.notification("textDocument/publishDiagnostics")),
        ["E0305"]
    );
    client.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"radc": {"raypath": [lib.display().to_string()]}}}),
    );
    assert_eq!(
        checked_codes(&client.notification("textDocument/publishDiagnostics")),
        Vec::<String>::new()
    );
    client.shutdown();
}

#[test]
fn a_rif_makes_its_files_one_scene() {
    let ws = workspace();
    let dir = ws.path.parent().expect("scene folder").to_path_buf();
    let walls = "paint polygon wall\n0\n0\n9 0 0 0 1 0 0 1 1 0\n";
    std::fs::write(
        dir.join("basic.mat"),
        "void plastic paint\n0\n0\n5 .5 .5 .5 0 0\n",
    )
    .expect("mat");
    std::fs::write(dir.join("walls.rad"), walls).expect("walls");
    std::fs::write(dir.join("alone.rad"), walls).expect("alone");
    let walls_uri = file_uri(&dir.join("walls.rad"));
    let alone_uri = file_uri(&dir.join("alone.rad"));
    let mut client = Client::start();
    initialize(&mut client, json!(null));

    // Without a rif, the material is undefined.
    open(&mut client, &alone_uri, walls);
    assert_eq!(
        codes(&client.notification("textDocument/publishDiagnostics")),
        ["E0301"]
    );

    std::fs::write(
        dir.join("room.rif"),
        "materials = basic.mat\nscene = walls.rad\n",
    )
    .expect("rif");
    open(&mut client, &walls_uri, walls);
    let published = client.notification("textDocument/publishDiagnostics");
    assert_eq!(published["uri"], walls_uri.as_str());
    assert_eq!(codes(&published), Vec::<String>::new());

    // Navigation reaches into the rif's earlier files.
    let mat_uri = format!(
        "file://{}",
        dir.join("basic.mat").canonicalize().expect("mat").display()
    );
    let definition = client.request(
        "textDocument/definition",
        at(&walls_uri, json!({"line": 0, "character": 2})),
    );
    assert_eq!(
        definition,
        json!({"uri": mat_uri, "range": range(0, 13, 0, 18)})
    );
    let hover = client.request(
        "textDocument/hover",
        at(&walls_uri, json!({"line": 0, "character": 2})),
    );
    let text = hover["contents"]["value"].as_str().unwrap_or_default();
    assert!(
        text.starts_with("**paint** — plastic (material), defined on line 1 of basic.mat"),
        "{text}"
    );
    let mut params = at(&walls_uri, json!({"line": 0, "character": 2}));
    params["context"] = json!({"includeDeclaration": true});
    let references = client.request("textDocument/references", params);
    assert_eq!(
        references,
        json!([{"uri": mat_uri, "range": range(0, 13, 0, 18)}, {"uri": walls_uri, "range": range(0, 0, 0, 5)}])
    );
    let completion = client.request(
        "textDocument/completion",
        at(&walls_uri, json!({"line": 4, "character": 0})),
    );
    let labels: Vec<&str> = completion
        .as_array()
        .map(|a| a.iter().filter_map(|i| i["label"].as_str()).collect())
        .unwrap_or_default();
    assert_eq!(labels, ["void", "paint"]);

    // The material file changes on disk: a watched-file event re-checks.
    std::fs::write(
        dir.join("basic.mat"),
        "void plastic other\n0\n0\n5 .5 .5 .5 0 0\n",
    )
    .expect("mat");
    client.notify("workspace/didChangeWatchedFiles", json!({"changes": []}));
    let mut walls_codes = None;
    for _ in 0..2 {
        let published = client.notification("textDocument/publishDiagnostics");
        if published["uri"] == walls_uri.as_str() {
            walls_codes = Some(codes(&published));
        }
    }
    assert_eq!(walls_codes, Some(vec!["E0301".to_string()]));
    client.shutdown();
}

#[test]
fn rif_documents_get_no_analysis() {
    let ws = workspace();
    let dir = ws.path.parent().expect("folder").to_path_buf();
    let mut client = Client::start();
    initialize(&mut client, json!(null));
    let uri = file_uri(&dir.join("p.rif"));
    open(&mut client, &uri, "scene = a.rad\n");
    let hover = client.request(
        "textDocument/hover",
        at(&uri, json!({"line": 0, "character": 0})),
    );
    assert_eq!(hover, Value::Null);
    // Publishing nothing for it: the next diagnostics are the scene's.
    open(&mut client, &ws.uri, TIDY);
    assert_eq!(
        client.notification("textDocument/publishDiagnostics")["uri"],
        ws.uri.as_str()
    );
    client.shutdown();
}

#[test]
fn a_burst_of_edits_ends_with_the_last_texts_diagnostics() {
    let ws = workspace();
    let uri = ws.uri.as_str();
    let mut client = Client::start();
    initialize(&mut client, json!(null));
    open(&mut client, uri, TIDY);
    client.notification("textDocument/publishDiagnostics");
    // Versions 2..=40 alternate between broken and fixed; the last one is broken.
    for version in 2..=40 {
        let text = if version % 2 == 0 { BROKEN } else { TIDY };
        change(&mut client, uri, version, text);
    }
    let last = loop {
        let published = client.notification("textDocument/publishDiagnostics");
        if published["version"] == 40 {
            break published;
        }
    };
    assert_eq!(codes(&last), ["E0202"]);
    // Nothing older arrives after it.
    let hover = client.request(
        "textDocument/hover",
        at(uri, json!({"line": 5, "character": 6})),
    );
    assert_eq!(hover["range"], range(5, 4, 5, 10));
    assert!(
        client
            .unread
            .iter()
            .all(|m| m["params"]["version"] == 40
                || m["method"] != "textDocument/publishDiagnostics")
    );
    client.shutdown();
}

/// (code, message) of each diagnostic `radc check --format json` reports for `path`.
fn cli_said(path: &std::path::Path) -> Vec<(String, String)> {
    let out = Command::new(env!("CARGO_BIN_EXE_radc"))
        .args(["check", "--format", "json"])
        .arg(path)
        .output()
        .expect("radc check runs");
    let mut said: Vec<(String, String)> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| serde_json::from_str::<Value>(l).ok())
        .map(|d| {
            (
                d["code"].as_str().unwrap_or("").into(),
                d["message"].as_str().unwrap_or("").into(),
            )
        })
        .collect();
    said.sort();
    said
}

fn lsp_said(published: &Value) -> Vec<(String, String)> {
    let mut said: Vec<(String, String)> = published["diagnostics"]
        .as_array()
        .map(|a| {
            a.iter()
                .map(|d| {
                    (
                        d["code"].as_str().unwrap_or("").into(),
                        d["message"].as_str().unwrap_or("").into(),
                    )
                })
                .collect()
        })
        .unwrap_or_default();
    said.sort();
    said
}

#[test]
fn built_in_generators_expand_as_radc_check_expands_them() {
    let ws = workspace();
    let uri = ws.uri.as_str();
    let text = "void plastic paint\n0\n0\n5 .5 .5 .5 0 0\n\n!genbox paint box 1 1 1\n!genbox nothing b 1 1 1\n!genbox\n";
    std::fs::write(&ws.path, text).expect("write scene");
    let mut client = Client::start();
    initialize(&mut client, json!(null));
    open(&mut client, uri, text);
    let published = client.notification("textDocument/publishDiagnostics");
    let said = lsp_said(&published);
    assert_eq!(said, cli_said(&ws.path));
    let codes: Vec<&str> = said.iter().map(|(c, _)| c.as_str()).collect();
    assert!(
        codes.contains(&"E0301") && !codes.contains(&"W0303"),
        "{said:?}"
    );
    // The undefined modifier inside genbox's output is shown on the command line.
    let e0301 = published["diagnostics"]
        .as_array()
        .and_then(|a| a.iter().find(|d| d["code"] == "E0301"))
        .cloned()
        .unwrap_or_default();
    assert_eq!(e0301["range"]["start"]["line"], 6);
    client.shutdown();
}

/// `path` as a `file:` URI, percent-encoded: the shared corpus has folders with spaces in
/// their names (`test/test data/`), which a URI cannot hold as they are.
fn file_uri(path: &std::path::Path) -> String {
    let mut uri = String::from("file://");
    for &b in path.to_string_lossy().as_bytes() {
        if b.is_ascii_alphanumeric() || b"/-._~".contains(&b) {
            uri.push(char::from(b));
        } else {
            uri.push_str(&format!("%{b:02X}"));
        }
    }
    uri
}

fn corpus_scenes(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            corpus_scenes(&p, out);
        } else if p.extension().is_some_and(|x| x == "rad") {
            out.push(p);
        }
    }
}

/// Every scene of the own corpus gets the same codes and messages from the server as
/// from `radc check FILE`.
#[test]
fn the_server_says_what_radc_check_says_across_the_corpora() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    corpus_scenes(&root.join("tests/data/scenes"), &mut files);
    assert_server_says_what_radc_check_says(files, 50);
}

/// The same for Radiance's test scenes in `../shared/corpus` (skipped visibly without it).
#[test]
fn the_server_says_what_radc_check_says_across_the_shared_corpus() {
    let Some(corpus) = radc_oracle::shared_corpus_or_skip(
        "lsp_e2e::the_server_says_what_radc_check_says_across_the_shared_corpus",
    ) else {
        return;
    };
    let mut files = Vec::new();
    corpus_scenes(&corpus, &mut files);
    // Most of them sit beside a `.rif` and are left out (see below).
    assert_server_says_what_radc_check_says(files, 10);
}

/// Opens each scene in one server and compares what it publishes with `radc check`; at
/// least `at_least` scenes must be compared.
fn assert_server_says_what_radc_check_says(mut files: Vec<std::path::PathBuf>, at_least: usize) {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    files.sort();
    let mut client = Client::start();
    initialize(&mut client, json!(null));
    let mut compared = 0;
    let mut mismatches = Vec::new();
    for path in files {
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue; // not UTF-8: the editor would not hold the same text
        };
        let path = path.canonicalize().unwrap_or(path);
        // A .rif beside the file changes what the server checks it with.
        let has_rif = std::fs::read_dir(path.parent().unwrap_or(root))
            .map(|d| {
                d.flatten()
                    .any(|e| e.path().extension().is_some_and(|x| x == "rif"))
            })
            .unwrap_or(false);
        if has_rif {
            continue;
        }
        let uri = file_uri(&path);
        open(&mut client, &uri, &text);
        let published = loop {
            let p = client.notification("textDocument/publishDiagnostics");
            if p["uri"] == uri.as_str() {
                break p;
            }
        };
        client.notify(
            "textDocument/didClose",
            json!({"textDocument": {"uri": uri}}),
        );
        compared += 1;
        let (lsp, cli) = (lsp_said(&published), cli_said(&path));
        if lsp != cli {
            mismatches.push(format!("{}:\n  lsp {lsp:?}\n  cli {cli:?}", path.display()));
        }
    }
    client.shutdown();
    eprintln!("compared {compared} scenes");
    assert!(compared >= at_least, "compared {compared}");
    assert!(
        mismatches.is_empty(),
        "{} of {compared} differ:\n{}",
        mismatches.len(),
        mismatches.join("\n")
    );
}

const CAL: &str = "k : 2 * 3;\nscale(x) = x * k;\nrefl = scale(Dx) + .5;\nbad = sinn(1);\n";
const SHADED: &str = "void brightfunc shade\n2 refl f.cal\n0\n0\n\nshade plastic red\n0\n0\n5 .5 .5 .5 0 0\n\nred sphere ball\n0\n0\n4 0 0 0 1\n";

/// A folder with `f.cal` and `shaded.rad`, which uses it, both on disk.
fn calcomp_workspace() -> (tempfile::TempDir, String, String, std::path::PathBuf) {
    let dir = tempfile::tempdir().expect("temp dir");
    let root = dir.path().canonicalize().expect("canonical");
    std::fs::write(root.join("f.cal"), CAL).expect("cal");
    std::fs::write(root.join("shaded.rad"), SHADED).expect("scene");
    let cal = file_uri(&root.join("f.cal"));
    let scene = file_uri(&root.join("shaded.rad"));
    (dir, cal, scene, root)
}

fn markdown(hover: &Value) -> &str {
    hover["contents"]["value"].as_str().unwrap_or_default()
}

#[test]
fn calcomp_documents_are_checked_and_navigable() {
    let (_dir, cal, scene, root) = calcomp_workspace();
    let mut client = Client::start();
    let init = initialize(&mut client, json!(null));
    for provider in ["workspaceSymbolProvider", "codeActionProvider"] {
        assert_eq!(init["capabilities"][provider], true, "{provider}");
    }
    open(&mut client, &cal, CAL);
    // The diagnostics `radc check f.cal` gives, word for word.
    let published = client.notification("textDocument/publishDiagnostics");
    assert_eq!(published["uri"], cal.as_str());
    assert_eq!(lsp_said(&published), cli_said(&root.join("f.cal")));
    assert_eq!(
        published["diagnostics"],
        json!([{
            "range": range(3, 6, 3, 13),
            "severity": 2,
            "code": "W0606",
            "source": "radc",
            "message": "function 'sinn' is not defined in this file",
            "relatedInformation": [{
                "location": {"uri": cal, "range": range(3, 6, 3, 13)},
                "message": "hint: did you mean 'sin'?"
            }]
        }])
    );

    // Hover: a constant with its value, a parameter, a library name.
    let hover = client.request("textDocument/hover", at(&cal, pos(CAL, "k;", 0, 0)));
    assert_eq!(
        markdown(&hover),
        "**k** — constant (`:`), defined on line 1\n\n```calcomp\nk : 2 * 3\n```\n\nvalue: `6`"
    );
    assert_eq!(hover["range"], range(1, 15, 1, 16));
    let hover = client.request("textDocument/hover", at(&cal, pos(CAL, "x *", 0, 0)));
    assert_eq!(markdown(&hover), "**x** — parameter 1 of **scale**");
    let hover = client.request("textDocument/hover", at(&cal, pos(CAL, "Dx", 0, 1)));
    assert_eq!(
        markdown(&hover),
        "**Dx** — Dx: ray direction (renderer, per ray)"
    );
    let hover = client.request("textDocument/hover", at(&cal, pos(CAL, "scale(Dx", 0, 0)));
    assert_eq!(
        markdown(&hover),
        "**scale** — function of 1 parameter (`=`), defined on line 2\n\n```calcomp\nscale(x) = x * k\n```"
    );

    // Definition, references, document symbols, completion.
    let definition = client.request("textDocument/definition", at(&cal, pos(CAL, "k;", 0, 0)));
    assert_eq!(definition, json!({"uri": cal, "range": range(0, 0, 0, 1)}));
    let mut params = at(&cal, pos(CAL, "scale", 0, 1));
    params["context"] = json!({"includeDeclaration": true});
    let references = client.request("textDocument/references", params);
    assert_eq!(
        references,
        json!([{"uri": cal, "range": range(1, 0, 1, 5)}, {"uri": cal, "range": range(2, 7, 2, 12)}])
    );
    let symbols = client.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": cal}}),
    );
    let outline: Vec<(String, u64, String)> = symbols
        .as_array()
        .map(|a| {
            a.iter()
                .map(|s| {
                    let name = s["name"].as_str().unwrap_or_default().to_string();
                    let detail = s["detail"].as_str().unwrap_or_default().to_string();
                    (name, s["kind"].as_u64().unwrap_or(0), detail)
                })
                .collect()
        })
        .unwrap_or_default();
    assert_eq!(
        outline,
        [
            ("k".to_string(), 14, ":".to_string()),
            ("scale".to_string(), 12, "(x) =".to_string()),
            ("refl".to_string(), 13, "=".to_string()),
            ("bad".to_string(), 13, "=".to_string())
        ]
    );
    let completion = client.request("textDocument/completion", at(&cal, pos(CAL, "x * k", 0, 4)));
    let labels: Vec<&str> = completion
        .as_array()
        .map(|a| a.iter().filter_map(|i| i["label"].as_str()).collect())
        .unwrap_or_default();
    assert_eq!(&labels[..6], ["x", "bad", "refl", "scale", "k", "acos"]);
    assert!(labels.contains(&"noise3") && labels.contains(&"Dx") && labels.contains(&"PI"));

    // A quick fix for the misspelled function.
    let actions = client.request(
        "textDocument/codeAction",
        json!({"textDocument": {"uri": cal}, "range": range(3, 6, 3, 13),
               "context": {"diagnostics": published["diagnostics"]}}),
    );
    assert_eq!(actions[0]["title"], "Change to 'sin'");
    assert_eq!(actions[0]["kind"], "quickfix");
    assert_eq!(
        actions[0]["edit"]["changes"][cal.as_str()],
        json!([{"range": range(3, 6, 3, 10), "newText": "sin"}])
    );

    // From the scene into the function file, and back.
    open(&mut client, &scene, SHADED);
    let definition = client.request(
        "textDocument/definition",
        at(&scene, pos(SHADED, "refl", 0, 1)),
    );
    assert_eq!(definition, json!({"uri": cal, "range": range(2, 0, 2, 4)}));
    let mut params = at(&cal, pos(CAL, "refl", 0, 0));
    params["context"] = json!({"includeDeclaration": true});
    let references = client.request("textDocument/references", params);
    assert_eq!(
        references,
        json!([{"uri": cal, "range": range(2, 0, 2, 4)}, {"uri": scene, "range": range(1, 2, 1, 6)}])
    );
    let rename = client.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": scene}, "position": pos(SHADED, "refl", 0, 2), "newName": "shine"}),
    );
    assert_eq!(
        rename,
        json!({"changes": {
            cal.as_str(): [{"range": range(2, 0, 2, 4), "newText": "shine"}],
            scene.as_str(): [{"range": range(1, 2, 1, 6), "newText": "shine"}]
        }})
    );
    let rename = client.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": cal}, "position": pos(CAL, "x)", 0, 0), "newName": "t"}),
    );
    assert_eq!(
        rename,
        json!({"changes": {cal.as_str(): [
            {"range": range(1, 6, 1, 7), "newText": "t"},
            {"range": range(1, 11, 1, 12), "newText": "t"}
        ]}})
    );
    // Not a name: refused.
    let rename = client.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": cal}, "position": pos(CAL, "k", 0, 0), "newName": "2k"}),
    );
    assert_eq!(rename, Value::Null);

    // Workspace symbols across both documents.
    let found = client.request("workspace/symbol", json!({"query": "sha"}));
    assert_eq!(
        found,
        json!([{"name": "shade", "kind": 23, "location": {"uri": scene, "range": range(0, 16, 0, 21)}, "containerName": "shaded.rad"}])
    );
    let found = client.request("workspace/symbol", json!({"query": "scal"}));
    assert_eq!(
        found,
        json!([{"name": "scale", "kind": 12, "location": {"uri": cal, "range": range(1, 0, 1, 5)}, "containerName": "f.cal"}])
    );

    client.shutdown();
}

#[test]
fn an_unsaved_function_file_is_what_scenes_read() {
    let (_dir, cal, scene, _root) = calcomp_workspace();
    let mut client = Client::start();
    initialize(&mut client, json!(null));
    open(&mut client, &cal, CAL);
    client.notification("textDocument/publishDiagnostics");
    open(&mut client, &scene, SHADED);
    let published = client.notification("textDocument/publishDiagnostics");
    assert_eq!(
        (published["uri"].as_str(), checked_codes(&published)),
        (Some(scene.as_str()), vec![])
    );
    // An unsaved edit of the function file is what the scene's check reads.
    change(&mut client, &cal, 2, "k : 6;\n");
    let mut scene_codes = None;
    for _ in 0..3 {
        let published = client.notification("textDocument/publishDiagnostics");
        if published["uri"] == scene.as_str() {
            scene_codes = Some(checked_codes(&published));
            break;
        }
    }
    assert_eq!(scene_codes, Some(vec!["E0601".to_string()]));
    // Saved as it was: the scene reads the disk again once the document closes.
    client.notify(
        "textDocument/didClose",
        json!({"textDocument": {"uri": cal}}),
    );
    change(&mut client, &scene, 2, SHADED);
    loop {
        let published = client.notification("textDocument/publishDiagnostics");
        if published["uri"] == scene.as_str() {
            assert_eq!(checked_codes(&published), Vec::<String>::new());
            break;
        }
    }
    client.shutdown();
}

#[test]
fn semantic_tokens_say_what_each_word_is() {
    let ws = workspace();
    let dir = ws.path.parent().expect("folder").to_path_buf();
    let mut client = Client::start();
    let init = initialize(&mut client, json!(null));
    let legend = &init["capabilities"]["semanticTokensProvider"]["legend"];
    assert_eq!(
        legend["tokenTypes"],
        json!([
            "keyword",
            "type",
            "variable",
            "number",
            "string",
            "comment",
            "macro",
            "function",
            "parameter",
            "operator"
        ])
    );
    assert_eq!(
        legend["tokenModifiers"],
        json!(["declaration", "defaultLibrary"])
    );
    let scene = "# lamp\n!genbox m b 1 1 1\nm sphere s\n0\n0\n4 0 0 0 .5\n";
    open(&mut client, &ws.uri, scene);
    let tokens = client.request(
        "textDocument/semanticTokens/full",
        json!({"textDocument": {"uri": ws.uri}}),
    );
    assert_eq!(
        tokens["data"],
        json!([
            0, 0, 6, 5, 0, // # lamp: comment
            1, 0, 17, 6, 0, // the command
            1, 0, 1, 1, 0, // m: modifier
            0, 2, 6, 0, 0, // sphere: type keyword
            0, 7, 1, 2, 1, // s: declared name
            1, 0, 1, 3, 0, 1, 0, 1, 3, 0, 1, 0, 1, 3, 0, 0, 2, 1, 3, 0, 0, 2, 1, 3, 0, 0, 2, 1, 3,
            0, 0, 2, 2, 3, 0
        ])
    );
    let cal = file_uri(&dir.join("g.cal"));
    open(&mut client, &cal, "f(x) = sin(x)*2;\n");
    let tokens = client.request(
        "textDocument/semanticTokens/full",
        json!({"textDocument": {"uri": cal}}),
    );
    assert_eq!(
        tokens["data"],
        json!([
            0, 0, 1, 7, 1, 0, 2, 1, 8, 1, 0, 3, 1, 9, 0, 0, 2, 3, 7, 2, 0, 4, 1, 8, 0, 0, 2, 1, 9,
            0, 0, 1, 1, 3, 0
        ])
    );
    client.shutdown();
}

#[test]
fn a_misspelled_modifier_gets_a_quick_fix() {
    let ws = workspace();
    let uri = ws.uri.as_str();
    let text = "void plastic red\n0\n0\n5 .5 .1 .1 0 0\nrd sphere ball\n0\n0\n4 0 0 0 1\n";
    let mut client = Client::start();
    initialize(&mut client, json!(null));
    open(&mut client, uri, text);
    let published = client.notification("textDocument/publishDiagnostics");
    let undefined: Vec<Value> = published["diagnostics"]
        .as_array()
        .map(|a| a.iter().filter(|d| d["code"] == "E0301").cloned().collect())
        .unwrap_or_default();
    assert_eq!(undefined.len(), 1, "{published}");
    let actions = client.request(
        "textDocument/codeAction",
        json!({"textDocument": {"uri": uri}, "range": range(4, 0, 4, 2),
               "context": {"diagnostics": published["diagnostics"]}}),
    );
    assert_eq!(
        actions,
        json!([{
            "title": "Change to 'red'",
            "kind": "quickfix",
            "diagnostics": undefined,
            "edit": {"changes": {uri: [{"range": range(4, 0, 4, 2), "newText": "red"}]}},
            "isPreferred": true
        }])
    );
    client.shutdown();
}

#[test]
fn renaming_a_material_reaches_the_scenes_of_its_rif() {
    let dir = tempfile::tempdir().expect("temp dir");
    let root = dir.path().canonicalize().expect("canonical");
    let mat = "void plastic paint\n0\n0\n5 .5 .5 .5 0 0\n";
    let walls = "paint polygon wall\n0\n0\n9 0 0 0 1 0 0 1 1 0\n";
    // table.rad redefines paint after its first use: later uses are its own.
    let table = "paint sphere leg\n0\n0\n4 0 0 0 1\nvoid plastic paint\n0\n0\n5 1 1 1 0 0\npaint sphere top\n0\n0\n4 0 0 1 1\n";
    std::fs::write(root.join("basic.mat"), mat).expect("mat");
    std::fs::write(root.join("walls.rad"), walls).expect("walls");
    std::fs::write(root.join("table.rad"), table).expect("table");
    std::fs::write(
        root.join("room.rif"),
        "materials = basic.mat\nscene = walls.rad table.rad\n",
    )
    .expect("rif");
    let uri = |name: &str| file_uri(&root.join(name));
    let mut client = Client::start();
    initialize(&mut client, json!(null));
    open(&mut client, &uri("basic.mat"), mat);
    client.notification("textDocument/publishDiagnostics");
    let rename = client.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": uri("basic.mat")}, "position": {"line": 0, "character": 14}, "newName": "white"}),
    );
    let edit = |l0, c0, c1| json!([{"range": range(l0, c0, l0, c1), "newText": "white"}]);
    assert_eq!(
        rename,
        json!({"changes": {
            uri("basic.mat"): edit(0, 13, 18),
            uri("walls.rad"): edit(0, 0, 5),
            uri("table.rad"): edit(0, 0, 5)
        }})
    );
    // From a use in a scene file, the same edit.
    open(&mut client, &uri("walls.rad"), walls);
    let again = client.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": uri("walls.rad")}, "position": {"line": 0, "character": 1}, "newName": "white"}),
    );
    assert_eq!(again, rename);
    client.shutdown();
}

#[test]
fn an_edit_reparses_only_the_edited_file() {
    let (_dir, cal, scene, root) = calcomp_workspace();
    let mut child_env = Client::start_with_env(&[("RADC_LSP_STATS", "1")]);
    let client = &mut child_env;
    initialize(client, json!(null));
    open(client, &cal, CAL);
    client.notification("textDocument/publishDiagnostics");
    open(client, &scene, SHADED);
    client.notification("textDocument/publishDiagnostics");
    let counts = |client: &mut Client| client.request("radc/stats", Value::Null)["parses"].clone();
    let cal_path = root.join("f.cal").display().to_string();
    let scene_path = root.join("shaded.rad").display().to_string();
    assert_eq!(
        counts(client),
        json!({cal_path.as_str(): 1, scene_path.as_str(): 1})
    );
    // A range edit (incremental sync): one character of the scene.
    let one_char = |version, line, start, end, text: &str| {
        json!({"textDocument": {"uri": scene, "version": version}, "contentChanges": [
            {"range": range(line, start, line, end), "text": text}]})
    };
    let statements = |client: &mut Client| {
        let stats = client.request("radc/stats", Value::Null);
        (
            stats["whole_parses"].clone(),
            stats["statements_read"][&scene_path].clone(),
        )
    };
    let (whole, opened) = statements(client);
    client.notify("textDocument/didChange", one_char(2, 8, 3, 4, "6"));
    let published = client.notification("textDocument/publishDiagnostics");
    assert_eq!(
        (published["version"].clone(), checked_codes(&published)),
        (json!(2), Vec::<String>::new())
    );
    assert_eq!(
        counts(client),
        json!({cal_path.as_str(): 1, scene_path.as_str(): 2})
    );
    // Of the scene, only the edited statement was read again.
    let after = statements(client);
    assert_eq!(after.0, whole);
    assert_eq!(after.1.as_u64(), opened.as_u64().map(|n| n + 1));
    client.notify("textDocument/didChange", one_char(3, 10, 1, 2, ""));
    let published = client.notification("textDocument/publishDiagnostics");
    let undefined: Vec<&Value> = published["diagnostics"]
        .as_array()
        .map(|a| a.iter().filter(|d| d["code"] == "E0301").collect())
        .unwrap_or_default();
    assert_eq!(undefined.len(), 1, "{published}");
    assert_eq!(undefined[0]["range"], range(10, 0, 10, 2));
    assert_eq!(
        undefined[0]["message"],
        "modifier 'rd' is not defined before this point"
    );
    assert_eq!(
        counts(client),
        json!({cal_path.as_str(): 1, scene_path.as_str(): 3})
    );
    change(client, &cal, 2, &CAL.replace("2 * 3", "2 * 4"));
    for _ in 0..2 {
        client.notification("textDocument/publishDiagnostics");
    }
    assert_eq!(
        counts(client),
        json!({cal_path.as_str(): 2, scene_path.as_str(): 3})
    );
    child_env.shutdown();
}
