// Starts `threadcheck lsp` for G-code files: diagnostics at each thread-making operation,
// hovers with every check, the correction as a quick fix.
const vscode = require("vscode");
const { LanguageClient } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const config = vscode.workspace.getConfiguration("threadcheck");
  const command = config.get("path", "threadcheck");
  client = new LanguageClient(
    "threadcheck",
    "threadcheck",
    { run: { command, args: ["lsp"] }, debug: { command, args: ["lsp"] } },
    {
      documentSelector: [{ scheme: "file", language: "gcode" }],
      initializationOptions: config.get("options", {}),
    }
  );
  context.subscriptions.push(client);
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
