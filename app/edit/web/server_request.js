// Requests of the editor's pages to the server that served them (`cutaway edit`; doc/editor.md,
// Security and Limits): every request to /api/ carries the server's token, which the server
// wrote into the page's meta tag cutaway-token; a busy server (503) is asked again after the
// time its Retry-After says.

/// The token of the server that served the page; empty when a plain file server served it
/// (the cutting page then loads files of `cutaway volume`).
export const token = document.querySelector('meta[name="cutaway-token"]')?.content ?? '';

/// fetch(url, init) with the page's token in the X-Cutaway-Token header, asked again after its
/// Retry-After (seconds; 1 when absent) while the answer is 503. Rejects with an AbortError
/// when init.signal aborts, as fetch does.
export async function ask(url, init = {}) {
  const headers = { ...(init.headers ?? {}), ...(token ? { 'X-Cutaway-Token': token } : {}) };
  for (;;) {
    const answer = await fetch(url, { ...init, headers });
    if (answer.status !== 503) return answer;
    const seconds = Number(answer.headers.get('Retry-After')) || 1;
    await new Promise((resolve) => setTimeout(resolve, seconds * 1000));
    init.signal?.throwIfAborted();
  }
}
