/*
 * Web workers for the site opened from the file system (file://), where browsers refuse
 * `new Worker(...)`: the worker script runs in a hidden iframe of the page instead, and messages
 * cross between the two as events. Material's search runs in a worker; its `offline` plugin
 * inlines the search index and would load a shim like this one from a CDN, which mkdocs.yml
 * replaces with this local file (`extra.polyfills`) so that the site needs no network.
 * Enough for the search worker (English: no importScripts); over http(s) nothing is replaced.
 */
(function () {
  "use strict";
  if (location.protocol !== "file:" || typeof EventTarget !== "function") return;

  class FrameWorker extends EventTarget {
    constructor(url) {
      super();
      this.onmessage = null;
      this.onerror = null;
      const frame = document.createElement("iframe");
      frame.hidden = true;
      document.body.appendChild(frame);
      this.frame = frame;
      const scope = frame.contentWindow;
      // The worker's global postMessage hands a copy of the data to the page, asynchronously.
      scope.postMessage = (data) => setTimeout(() => this.deliver(structuredClone(data)), 0);
      scope.importScripts = () => {
        throw new Error("importScripts is not available to a worker opened from file://");
      };
      this.ready = new Promise((resolve, reject) => {
        const script = scope.document.createElement("script");
        script.src = new URL(url, location.href).href;
        script.onload = resolve;
        script.onerror = (event) => {
          this.fail(`could not load the worker script ${script.src}`);
          reject(event);
        };
        scope.document.body.appendChild(script);
      });
    }

    deliver(data) {
      const event = new MessageEvent("message", { data });
      if (typeof this.onmessage === "function") this.onmessage(event);
      this.dispatchEvent(event);
    }

    fail(message) {
      const event = new ErrorEvent("error", { message });
      if (typeof this.onerror === "function") this.onerror(event);
      this.dispatchEvent(event);
    }

    postMessage(data) {
      this.ready.then(() => {
        const scope = this.frame.contentWindow;
        if (scope) scope.dispatchEvent(new scope.MessageEvent("message", {
          data: scope.structuredClone(data),
        }));
      }, () => {});
    }

    terminate() {
      this.frame.remove();
    }
  }

  window.Worker = FrameWorker;
})();
