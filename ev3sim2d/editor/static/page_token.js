// The page token (ev3sim2d/editor/page_guard.py): the address `ev3sim2d edit` / `ev3sim2d live` prints
// ends in #token=...; a fragment never goes to a server nor into a Referer.  The page keeps the token in
// sessionStorage (this origin and port, this tab), takes it out of the address bar, and sends it as a
// header on every request with fetch - the event stream and the LCD images too - so it is never in a URL.
"use strict";

(function () {
  const KEY = "ev3sim2d-page-token";
  const HEADER = "X-Ev3sim2d-Token";

  function takeFromAddress() {
    const found = /(?:^#|&)token=([A-Za-z0-9_-]+)/.exec(window.location.hash);
    if (!found) return false;
    sessionStorage.setItem(KEY, found[1]);
    history.replaceState(null, "", window.location.pathname + window.location.search);
    return true;
  }
  takeFromAddress();
  // the student pastes a new address (the server was started again) into this tab: only the fragment
  // changes, so the page is not loaded again by the browser; take the new token and start afresh
  window.addEventListener("hashchange", () => { if (takeFromAddress()) window.location.reload(); });

  function token() {
    return sessionStorage.getItem(KEY) || "";
  }

  // fetch(path, options) with the token; same-origin only, never a cookie, never a referrer
  function pageFetch(path, options) {
    const given = options || {};
    const headers = new Headers(given.headers || {});
    headers.set(HEADER, token());
    return fetch(path, { ...given, headers: headers, credentials: "omit", referrerPolicy: "no-referrer", mode: "same-origin" });
  }

  // Server-Sent Events read with fetch (EventSource cannot send a header): onMessage(data) for each
  // `data:` line, onOpen() once connected, onError() when the stream breaks; it connects again after a
  // second, as EventSource would.  Returns a function that stops it.
  function pageEvents(path, onMessage, onOpen, onError) {
    let stopped = false;
    let controller = null;
    async function connect() {
      controller = new AbortController();
      try {
        const response = await pageFetch(path, { signal: controller.signal, cache: "no-store" });
        if (!response.ok || !response.body) throw new Error(`the server answered ${response.status}`);
        onOpen();
        const reader = response.body.getReader();
        const decoder = new TextDecoder();
        let buffer = "";
        for (;;) {
          const { value, done } = await reader.read();
          if (done) break;
          buffer += decoder.decode(value, { stream: true });
          let end;
          while ((end = buffer.indexOf("\n\n")) >= 0) {
            const block = buffer.slice(0, end);
            buffer = buffer.slice(end + 2);
            const data = block.split("\n").filter((l) => l.startsWith("data:")).map((l) => l.slice(5).trimStart());
            if (data.length) onMessage(data.join("\n"));
          }
        }
        throw new Error("the stream ended");
      } catch (err) {
        if (stopped) return;
        onError(err);
        setTimeout(connect, 1000);
      }
    }
    connect();
    return () => { stopped = true; if (controller) controller.abort(); };
  }

  window.PageToken = { fetch: pageFetch, events: pageEvents, has: () => token() !== "", header: HEADER };
})();
