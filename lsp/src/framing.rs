//! A guard in front of the protocol library: passes on only well-framed messages whose
//! body is JSON. tower-lsp-server answers a malformed body with a parse error but then
//! stops reading (its framed reader ends after the first error), which would take the
//! server down on one bad message; dropping such a message keeps it serving.

use tokio::io::{AsyncBufReadExt, AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt, BufReader};

/// Larger bodies are refused (and the stream ends) rather than allocated.
const MAX_BODY: usize = 1 << 28;

pub async fn forward_valid_frames(
    input: impl AsyncRead + Unpin,
    mut output: impl AsyncWrite + Unpin,
) {
    let mut input = BufReader::new(input);
    loop {
        let Some(length) = read_headers(&mut input).await else {
            return;
        };
        let Some(length) = length.filter(|&n| n <= MAX_BODY) else {
            eprintln!("radc lsp: a message without a usable Content-Length was dropped");
            if length.is_some() {
                return;
            }
            continue;
        };
        let mut body = vec![0; length];
        if input.read_exact(&mut body).await.is_err() {
            return;
        }
        if serde_json::from_slice::<serde::de::IgnoredAny>(&body).is_err() {
            eprintln!("radc lsp: a message that is not JSON was dropped");
            continue;
        }
        let header = format!("Content-Length: {length}\r\n\r\n");
        let sent = async {
            output.write_all(header.as_bytes()).await?;
            output.write_all(&body).await?;
            output.flush().await
        };
        if sent.await.is_err() {
            return;
        }
    }
}

/// Reads header lines up to the blank line; `None` at the end of input, else the
/// Content-Length if there was a valid one.
async fn read_headers(input: &mut (impl AsyncBufReadExt + Unpin)) -> Option<Option<usize>> {
    let mut length = None;
    let mut seen_any = false;
    loop {
        let mut line = String::new();
        if input.read_line(&mut line).await.ok()? == 0 {
            return None;
        }
        let line = line.trim();
        if line.is_empty() {
            if seen_any {
                return Some(length);
            }
            continue;
        }
        seen_any = true;
        if let Some((name, value)) = line.split_once(':')
            && name.trim().eq_ignore_ascii_case("content-length")
        {
            length = value.trim().parse().ok();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drops_bodies_that_are_not_json_and_keeps_the_rest() {
        let input: &[u8] = b"Content-Length: 7\r\n\r\n{hello}Content-Length: 2\r\n\r\n{}\
                             garbage\r\n\r\ncontent-length: 4\r\nContent-Type: x\r\n\r\nnull";
        let runtime = tokio::runtime::Builder::new_current_thread().build();
        let mut out = Vec::new();
        if let Ok(rt) = runtime {
            rt.block_on(forward_valid_frames(input, &mut out));
        }
        assert_eq!(
            String::from_utf8_lossy(&out),
            "Content-Length: 2\r\n\r\n{}Content-Length: 4\r\n\r\nnull"
        );
    }
}
