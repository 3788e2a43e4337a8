"""motion-futures export: data, training, evaluation and ONNX export for the browser predictor."""
